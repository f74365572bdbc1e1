#pragma once
// The clip box's handles in the view (issue 22, point 1), as CloudCompare's and Potree's boxes
// have them: the centre moves the box (in the horizontal plane; with Shift, up and down), each
// face's handle moves that face along its normal while the opposite face stays, and the turn
// handle, beyond the top of the +x face, turns the box about the vertical through its centre.
// Plain geometry over a ClipBox and the pointer's rays: unit tests drive it without a window.

#include <array>
#include <cstdint>
#include <optional>

#include "engine/render/overlay_scene.h"
#include "engine/view/camera.h"
#include "engine/view/camera_controls.h"
#include "engine/view/clip_region.h"

namespace plumb::viewer {

enum class BoxHandle : std::uint8_t {
  kCentre,
  kXMin,
  kXMax,
  kYMin,
  kYMax,
  kZMin,
  kZMax,
  kTurn,
};
inline constexpr std::size_t kBoxHandleCount = 8;

// A box is never dragged thinner than this along any of its axes.
inline constexpr double kMinBoxHalfSize = 0.005;  // metres

// Where each handle is drawn, in BoxHandle order.
std::array<Eigen::Vector3d, kBoxHandleCount> boxHandlePositions(const view::ClipBox& box);

// The box's twelve edges, as pairs of corners (what the view draws).
std::array<std::array<Eigen::Vector3d, 2>, 12> boxEdges(const view::ClipBox& box);

// Draws the box's edges and its handles into `overlay`, `lit` brighter and larger.
void addClipBox(render::OverlayScene& overlay, const view::ClipBox& box, std::optional<BoxHandle> lit);

// The handle whose marker is nearest the pixel (x, y) of `camera`, within `radius_px`.
std::optional<BoxHandle> boxHandleAt(const view::ClipBox& box, const view::Camera& camera, double x_px, double y_px,
                                     double radius_px = 12.0);

// A drag of one handle: made at the press with the pointer's ray there, it gives the box for each
// later ray (the box as it was at the press, changed by how far the pointer went along what the
// handle follows). A ray within 5 degrees of parallel to what the handle follows (a line, a level
// plane) leaves the box as it was: a top face dragged from straight above does not move.
class BoxDrag {
 public:
  BoxDrag(const view::ClipBox& box, BoxHandle handle, const view::Ray& pressed, bool vertical);
  view::ClipBox boxFor(const view::Ray& ray) const;
  BoxHandle handle() const { return handle_; }

 private:
  view::ClipBox start_;
  BoxHandle handle_;
  bool vertical_;                           // the centre, moved up and down
  std::optional<Eigen::Vector3d> grabbed_;  // where the press met the plane dragged in
  std::optional<double> grabbed_along_;     // ... or the line dragged along
};

}  // namespace plumb::viewer
