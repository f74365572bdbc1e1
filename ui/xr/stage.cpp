#include "ui/xr/stage.h"

#include <algorithm>
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

WorldRay aimRay(const StagePlacement& placement, const Pose& aim) {
  return {placement.toWorld(aim.position),
          placement.directionToWorld(aim.orientation * Eigen::Vector3d(0.0, 0.0, -1.0))};
}

}  // namespace plumb::xr
