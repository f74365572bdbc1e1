#include "ui/xr/stage.h"

#include <algorithm>
#include <cassert>
#include <cmath>

namespace plumb::xr {
namespace {

// OpenXR's axes into the world's: x, y up, z back -> x, z up, y forward.
Eigen::Vector3d zUp(const Eigen::Vector3d& v) {
  return {v.x(), -v.z(), v.y()};
}

Eigen::Vector3d yUp(const Eigen::Vector3d& v) {
  return {v.x(), v.z(), -v.y()};
}

// The angle about z of a horizontal direction, from world +y.
double headingOf(const Eigen::Vector3d& world_direction) {
  return std::atan2(-world_direction.x(), world_direction.y());
}

}  // namespace

Eigen::Vector3d StagePlacement::toWorld(const Eigen::Vector3d& stage_point) const {
  return origin + scale * (Eigen::AngleAxisd(heading_rad, Eigen::Vector3d::UnitZ()) * zUp(stage_point));
}

Eigen::Vector3d StagePlacement::directionToWorld(const Eigen::Vector3d& stage_direction) const {
  return (Eigen::AngleAxisd(heading_rad, Eigen::Vector3d::UnitZ()) * zUp(stage_direction)).normalized();
}

Eigen::Vector3d StagePlacement::toStage(const Eigen::Vector3d& world_point) const {
  return yUp(Eigen::AngleAxisd(-heading_rad, Eigen::Vector3d::UnitZ()) * ((world_point - origin) / scale));
}

StagePlacement placementAt(const view::Camera& camera, const Pose& head, double scale) {
  const Eigen::Vector3d head_forward = zUp(head.orientation * Eigen::Vector3d(0.0, 0.0, -1.0));
  const Eigen::Vector3d camera_forward = view::viewDirection(camera);
  StagePlacement placement;
  placement.scale = scale;
  // A camera or head looking straight down has no heading: keep the stage's.
  const bool level_head = head_forward.head<2>().norm() > 1e-6;
  const bool level_camera = camera_forward.head<2>().norm() > 1e-6;
  placement.heading_rad = level_head && level_camera ? headingOf(camera_forward) - headingOf(head_forward) : 0.0;
  const Eigen::Vector3d head_from_origin =
      scale * (Eigen::AngleAxisd(placement.heading_rad, Eigen::Vector3d::UnitZ()) * zUp(head.position));
  placement.origin = camera.position - head_from_origin;
  return placement;
}

view::Camera eyeCamera(const StagePlacement& placement, const Pose& eye, const view::EyeFov& fov, int width, int height,
                       double near_stage_m) {
  view::Camera camera;
  camera.position = placement.toWorld(eye.position);
  const Eigen::Vector3d forward = placement.directionToWorld(eye.orientation * Eigen::Vector3d(0.0, 0.0, -1.0));
  camera.target = camera.position + placement.scale * forward;
  camera.up = placement.directionToWorld(eye.orientation * Eigen::Vector3d(0.0, 1.0, 0.0));
  camera.projection = view::Projection::kPerspective;
  camera.eye_fov = fov;
  camera.viewport_width_px = width;
  camera.viewport_height_px = height;
  camera.near_m = near_stage_m * placement.scale;
  camera.far_m = std::max(10'000.0, 100.0 * camera.near_m);
  return camera;
}

namespace {

// The heading of a stage direction about the stage's up, from -z (forward), counter-clockwise
// seen from above; 0 for a vertical direction.
double yawOf(const Eigen::Vector3d& stage_direction) {
  if (Eigen::Vector2d(stage_direction.x(), stage_direction.z()).norm() < 1e-9) return 0.0;
  return std::atan2(-stage_direction.x(), -stage_direction.z());
}

}  // namespace

Hold holdOf(const Pose& hand) {
  return {hand.position, yawOf(hand.orientation * Eigen::Vector3d(0.0, 0.0, -1.0)), 1.0};
}

Hold holdOf(const Pose& left, const Pose& right) {
  const Eigen::Vector3d across = right.position - left.position;
  // The line's heading, measured as a forward direction would be: turned a quarter to the left.
  return {0.5 * (left.position + right.position), yawOf(Eigen::Vector3d(across.z(), 0.0, -across.x())),
          std::max(across.norm(), 1e-3)};
}

StagePlacement dragged(const StagePlacement& start, const Hold& from, const Hold& to) {
  // In the stage, every world point q moves to to.point + k Ry(d)(q - from.point), k = to.span /
  // from.span, d the yaw's change. A turn about the stage's up is the same turn about the
  // world's z (the axes' map is a rotation), so the world-from-stage map becomes
  // q -> start(from.point + Ry(-d)(q - to.point) / k).
  StagePlacement moved;
  moved.scale = start.scale * from.span / to.span;
  moved.heading_rad = start.heading_rad - (to.yaw_rad - from.yaw_rad);
  const Eigen::Vector3d to_from_origin = moved.toWorld(to.point) - moved.origin;  // origin still zero
  moved.origin = start.toWorld(from.point) - to_from_origin;
  return moved;
}

StagePlacement walked(const StagePlacement& placement, const Eigen::Vector3d& stage_offset) {
  StagePlacement moved = placement;
  moved.origin += placement.toWorld(stage_offset) - placement.origin;
  return moved;
}

StagePlacement turned(const StagePlacement& placement, const Eigen::Vector3d& pivot, double angle_rad) {
  // The user turning left is the world turning right about them.
  return dragged(placement, {pivot, 0.0, 1.0}, {pivot, -angle_rad, 1.0});
}

StagePlacement modelOnTable(const StagePlacement& placement, const Eigen::Vector3d& bounds_min,
                            const Eigen::Vector3d& bounds_max, const Eigen::Vector3d& centre, double size_m) {
  StagePlacement model = placement;
  const double extent = std::max((bounds_max - bounds_min).maxCoeff(), 1e-6);
  model.scale = extent / size_m;
  const Eigen::Vector3d centre_from_origin = model.toWorld(centre) - model.origin;
  model.origin = 0.5 * (bounds_min + bounds_max) - centre_from_origin;
  return model;
}

view::Camera bothEyesCamera(const view::Camera& left, const view::Camera& right) {
  assert(left.eye_fov && right.eye_fov && "both eyes' cameras have off-axis frusta");
  const view::EyeFov& l = *left.eye_fov;
  const view::EyeFov& r = *right.eye_fov;
  const double tan_left = std::min(std::tan(l.left), std::tan(r.left));
  const double tan_right = std::max(std::tan(l.right), std::tan(r.right));
  view::Camera both = left;
  both.eye_fov =
      view::EyeFov{std::atan(tan_left), std::atan(tan_right), std::max(l.up, r.up), std::min(l.down, r.down)};
  // Back by half the eyes' distance over the narrower side's slope: each eye's outer side, a
  // ray from half that distance off the centre, then runs inside the union's side.
  const double half_apart = 0.5 * (right.position - left.position).norm();
  const double back = half_apart / std::max(std::min(-tan_left, tan_right), 0.1);
  const Eigen::Vector3d forward = view::viewDirection(left);
  both.position = 0.5 * (left.position + right.position) - back * forward;
  both.target = both.position + forward * (left.target - left.position).norm();
  // The same pixels a radian: the union is as many pixels wider as it spans more.
  const double eye_span = std::tan(l.right) - std::tan(l.left);
  both.viewport_width_px =
      static_cast<int>(std::lround(left.viewport_width_px * (tan_right - tan_left) / std::max(eye_span, 1e-6)));
  const double eye_height = std::tan(l.up) - std::tan(l.down);
  both.viewport_height_px = static_cast<int>(
      std::lround(left.viewport_height_px * (std::tan(both.eye_fov->up) - std::tan(both.eye_fov->down)) /
                  std::max(eye_height, 1e-6)));
  return both;
}

WorldRay aimRay(const StagePlacement& placement, const Pose& aim) {
  return {placement.toWorld(aim.position),
          placement.directionToWorld(aim.orientation * Eigen::Vector3d(0.0, 0.0, -1.0))};
}

}  // namespace plumb::xr
