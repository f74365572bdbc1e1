#include "ui/viewer/clip_box_handles.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace plumb::viewer {
namespace {

// The box's own axes: x and y turned by its yaw about the vertical, z up.
std::array<Eigen::Vector3d, 3> axesOf(const view::ClipBox& box) {
  const double c = std::cos(box.yaw_rad), s = std::sin(box.yaw_rad);
  return {Eigen::Vector3d(c, s, 0.0), Eigen::Vector3d(-s, c, 0.0), Eigen::Vector3d::UnitZ()};
}

// A face handle's axis (0, 1, 2) and side (-1, +1).
std::pair<int, double> faceOf(BoxHandle handle) {
  const int index = static_cast<int>(handle) - static_cast<int>(BoxHandle::kXMin);
  return {index / 2, index % 2 == 0 ? -1.0 : 1.0};
}

bool isFace(BoxHandle handle) {
  return handle != BoxHandle::kCentre && handle != BoxHandle::kTurn;
}

// A ray within this angle (5 degrees) of what a handle follows, a line along it or the plane it
// moves in, moves the handle nowhere: nearer parallel, a pixel would move it metres.
constexpr double kMinDragSine = 0.087;

std::optional<double> alongLine(const Eigen::Vector3d& point, const Eigen::Vector3d& axis, const view::Ray& ray) {
  if (axis.cross(ray.direction).norm() < kMinDragSine) return std::nullopt;
  return view::lineParameterNearestRay(point, axis, ray);
}

std::optional<Eigen::Vector3d> onLevel(const Eigen::Vector3d& point, const view::Ray& ray) {
  if (std::abs(ray.direction.z()) < kMinDragSine) return std::nullopt;
  return view::rayHitOnPlane(ray, point, Eigen::Vector3d::UnitZ());
}

double angleAbout(const Eigen::Vector3d& centre, const Eigen::Vector3d& point) {
  return std::atan2(point.y() - centre.y(), point.x() - centre.x());
}

}  // namespace

std::array<Eigen::Vector3d, kBoxHandleCount> boxHandlePositions(const view::ClipBox& box) {
  const std::array<Eigen::Vector3d, 3> axes = axesOf(box);
  std::array<Eigen::Vector3d, kBoxHandleCount> positions;
  positions[static_cast<std::size_t>(BoxHandle::kCentre)] = box.centre;
  for (std::size_t h = static_cast<std::size_t>(BoxHandle::kXMin); h <= static_cast<std::size_t>(BoxHandle::kZMax);
       ++h) {
    const auto [axis, side] = faceOf(static_cast<BoxHandle>(h));
    positions[h] = box.centre + side * box.half_size[axis] * axes[static_cast<std::size_t>(axis)];
  }
  // Beyond the top of the +x face, a quarter of the box's width out: clear of the face's handle.
  const double margin = std::max(0.25 * std::max(box.half_size.x(), box.half_size.y()), 0.1);
  positions[static_cast<std::size_t>(BoxHandle::kTurn)] =
      box.centre + (box.half_size.x() + margin) * axes[0] + box.half_size.z() * axes[2];
  return positions;
}

std::array<std::array<Eigen::Vector3d, 2>, 12> boxEdges(const view::ClipBox& box) {
  const std::array<Eigen::Vector3d, 3> axes = axesOf(box);
  const auto corner = [&](int i) {
    return Eigen::Vector3d(box.centre + (i & 1 ? 1.0 : -1.0) * box.half_size.x() * axes[0] +
                           (i & 2 ? 1.0 : -1.0) * box.half_size.y() * axes[1] +
                           (i & 4 ? 1.0 : -1.0) * box.half_size.z() * axes[2]);
  };
  std::array<std::array<Eigen::Vector3d, 2>, 12> edges;
  std::size_t n = 0;
  for (int i = 0; i < 8; ++i) {
    for (const int bit : {1, 2, 4}) {
      if ((i & bit) == 0) edges[n++] = {corner(i), corner(i | bit)};
    }
  }
  return edges;
}

void addClipBox(render::OverlayScene& overlay, const view::ClipBox& box, std::optional<BoxHandle> lit) {
  constexpr render::Rgba kEdge{255, 140, 0, 255};
  for (const auto& [a, b] : boxEdges(box)) overlay.lines.push_back({a, b, kEdge, 1.5f, true});
  const std::array<Eigen::Vector3d, kBoxHandleCount> positions = boxHandlePositions(box);
  // The turn handle's arm from the top of the +x face.
  const std::array<Eigen::Vector3d, 3> axes = axesOf(box);
  const Eigen::Vector3d arm = box.centre + box.half_size.x() * axes[0] + box.half_size.z() * axes[2];
  overlay.lines.push_back({arm, positions[static_cast<std::size_t>(BoxHandle::kTurn)], kEdge, 1.5f, true});
  for (std::size_t h = 0; h < positions.size(); ++h) {
    const auto handle = static_cast<BoxHandle>(h);
    const bool on = lit == handle;
    const render::Rgba colour = on                             ? render::Rgba{255, 255, 255, 255}
                                : handle == BoxHandle::kTurn   ? render::Rgba{255, 80, 200, 255}
                                : handle == BoxHandle::kCentre ? render::Rgba{255, 220, 0, 255}
                                                               : kEdge;
    overlay.markers.push_back({positions[h], colour, on ? 16.0f : 11.0f, true});
  }
}

std::optional<BoxHandle> boxHandleAt(const view::ClipBox& box, const view::Camera& camera, double x_px, double y_px,
                                     double radius_px) {
  const std::array<Eigen::Vector3d, kBoxHandleCount> positions = boxHandlePositions(box);
  std::optional<BoxHandle> best;
  double best_distance = std::numeric_limits<double>::infinity();
  for (std::size_t h = 0; h < positions.size(); ++h) {
    const std::optional<Eigen::Vector2d> pixel = view::pixelOf(camera, positions[h]);
    if (!pixel) continue;
    const double distance = (*pixel - Eigen::Vector2d(x_px, y_px)).norm();
    // Of handles drawn within half a pixel of each other the first wins: the centre over the top
    // face's handle, seen from above.
    if (distance <= radius_px && distance < best_distance - 0.5) {
      best = static_cast<BoxHandle>(h);
      best_distance = distance;
    }
  }
  return best;
}

BoxDrag::BoxDrag(const view::ClipBox& box, BoxHandle handle, const view::Ray& pressed, bool vertical)
    : start_(box), handle_(handle), vertical_(vertical && handle == BoxHandle::kCentre) {
  const std::array<Eigen::Vector3d, 3> axes = axesOf(box);
  if (isFace(handle)) {
    const auto [axis, side] = faceOf(handle);
    grabbed_along_ = alongLine(box.centre, axes[static_cast<std::size_t>(axis)], pressed);
  } else if (vertical_) {
    grabbed_along_ = alongLine(box.centre, axes[2], pressed);
  } else {
    // The centre and the turn handle move in the horizontal plane through the handle.
    grabbed_ = onLevel(boxHandlePositions(box)[static_cast<std::size_t>(handle)], pressed);
  }
}

view::ClipBox BoxDrag::boxFor(const view::Ray& ray) const {
  view::ClipBox box = start_;
  const std::array<Eigen::Vector3d, 3> axes = axesOf(start_);
  if (grabbed_along_) {
    const std::size_t axis = isFace(handle_) ? static_cast<std::size_t>(faceOf(handle_).first) : 2;
    const std::optional<double> along = alongLine(start_.centre, axes[axis], ray);
    if (!along) return box;
    const double moved = *along - *grabbed_along_;
    if (!isFace(handle_)) {
      box.centre += moved * axes[axis];
      return box;
    }
    // The face moves; the opposite one stays. Past it, the box keeps its least thickness there.
    const double side = faceOf(handle_).second;
    const double half = start_.half_size[static_cast<Eigen::Index>(axis)];
    const double opposite = -side * half;
    const double face = side * half + moved;
    const double new_half = std::max(0.5 * side * (face - opposite), kMinBoxHalfSize);
    box.half_size[static_cast<Eigen::Index>(axis)] = new_half;
    box.centre = start_.centre + (opposite + side * new_half) * axes[axis];
    return box;
  }
  if (!grabbed_) return box;
  const std::optional<Eigen::Vector3d> hit =
      onLevel(boxHandlePositions(start_)[static_cast<std::size_t>(handle_)], ray);
  if (!hit) return box;
  if (handle_ == BoxHandle::kCentre) {
    box.centre += Eigen::Vector3d(hit->x() - grabbed_->x(), hit->y() - grabbed_->y(), 0.0);
    return box;
  }
  // Turned by the angle the pointer went about the centre, kept within (-180, 180] degrees.
  const double turned = angleAbout(start_.centre, *hit) - angleAbout(start_.centre, *grabbed_);
  box.yaw_rad = std::remainder(start_.yaw_rad + turned, 2.0 * std::numbers::pi);
  return box;
}

}  // namespace plumb::viewer
