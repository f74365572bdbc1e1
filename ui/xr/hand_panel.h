#pragma once
// The palette in VR: a flat panel held in the left hand, like a tablet, showing the window's
// palette (a quad layer of the runtime's compositor), and where the right controller's ray
// meets it. Stage coordinates throughout (OpenXR's axes, metres).
//
// Plain data and math: copy freely, no thread-safety concerns.

#include <Eigen/Core>
#include <optional>

#include "ui/xr/stage.h"

namespace plumb::xr {

struct HandPanel {
  Pose pose;  // its centre; it faces its +z (towards the user's eyes)
  double width_m = 0.36, height_m = 0.2;
};

// The panel above the hand: 12 cm over the controller, tilted back 30 degrees towards the
// eyes, `width_m` wide and as tall as `aspect` (width over height) makes it.
HandPanel panelOnHand(const Pose& hand, double aspect, double width_m = 0.36);

// Where a ray from `aim` (its -z) meets the panel's front: (u, v) in [0, 1], u to the right
// and v down as image pixels go; nothing when it misses or meets it from behind.
std::optional<Eigen::Vector2d> panelPoint(const HandPanel& panel, const Pose& aim);

}  // namespace plumb::xr
