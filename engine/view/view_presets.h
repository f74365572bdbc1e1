#pragma once
// Standard views of a box (a cloud's bounds): top, front and side are orthographic views along
// -z, +y and -x that fit the box with a margin; iso is a perspective view from the front right
// above (direction (1, -1, 1)) that fits the box's bounding sphere. Used by `plumb render
// --view` and the viewer's view buttons.

#include <Eigen/Core>
#include <optional>
#include <string_view>

#include "engine/view/camera.h"

namespace plumb::view {

enum class ViewPreset : std::uint8_t { kTop, kFront, kSide, kIso };

// "top", "front", "side", "iso"; nothing for another name.
std::optional<ViewPreset> viewPresetNamed(std::string_view name);

// A valid camera of the given viewport that shows all of the box [min, max] (min <= max; a
// degenerate box is treated as one of 1 mm).
Camera presetCamera(ViewPreset preset, const Eigen::Vector3d& min, const Eigen::Vector3d& max, int width_px,
                    int height_px);

}  // namespace plumb::view
