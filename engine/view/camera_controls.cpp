#include "engine/view/camera_controls.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cassert>
#include <cmath>
#include <numbers>

namespace plumb::view {
namespace {

constexpr double kPoleMargin = std::numbers::pi / 180.0;  // one degree short of straight up or down

struct Axes {
  Eigen::Vector3d right, up, forward;
};

Axes axesOf(const Camera& camera) {
  const Eigen::Vector3d forward = viewDirection(camera);
  const Eigen::Vector3d right = forward.cross(camera.up).normalized();
  return {right, right.cross(forward), forward};
}

// The rotation of a look-around or an orbit: `pitch` about the camera's right axis (positive
// looks down), limited so that the view direction keeps kPoleMargin from the z axis, then `yaw`
// about world z. Applied to the view direction and the up vector alike, it turns the whole
// camera frame, so nothing rolls.
Eigen::Matrix3d turnRotation(const Axes& axes, double yaw, double pitch) {
  const double elevation = std::asin(std::clamp(axes.forward.z(), -1.0, 1.0));
  const double limit = std::numbers::pi / 2 - kPoleMargin;
  const double wanted = std::clamp(elevation - pitch, std::min(-limit, elevation), std::max(limit, elevation));
  // A rotation about right by a positive angle turns the view direction upwards.
  return (Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(wanted - elevation, axes.right))
      .toRotationMatrix();
}

}  // namespace

std::optional<Eigen::Vector2d> pixelOf(const Camera& camera, const Eigen::Vector3d& world) {
  const Eigen::Vector4d clip = projectionMatrix(camera) * viewMatrix(camera) * world.homogeneous();
  if (clip.w() <= 0.0) return std::nullopt;
  const Eigen::Vector2d ndc = clip.head<2>() / clip.w();
  return Eigen::Vector2d(0.5 * (ndc.x() + 1.0) * camera.viewport_width_px,
                         0.5 * (1.0 - ndc.y()) * camera.viewport_height_px);
}

Ray rayThroughPixel(const Camera& camera, double x_px, double y_px) {
  const Axes axes = axesOf(camera);
  const double dx = x_px - 0.5 * camera.viewport_width_px, dy = 0.5 * camera.viewport_height_px - y_px;
  if (camera.projection == Projection::kOrthographic) {
    const double scale = metresPerPixel(camera, 0.0);
    return {camera.position + axes.right * (dx * scale) + axes.up * (dy * scale), axes.forward};
  }
  const double scale = metresPerPixel(camera, 1.0);  // at one metre in front of the eye
  return {camera.position, (axes.forward + axes.right * (dx * scale) + axes.up * (dy * scale)).normalized()};
}

std::optional<double> lineParameterNearestRay(const Eigen::Vector3d& p, const Eigen::Vector3d& d, const Ray& ray) {
  const double b = d.dot(ray.direction);
  const double denominator = 1.0 - b * b;
  if (denominator < 1e-12) return std::nullopt;
  const Eigen::Vector3d w = p - ray.origin;
  return (b * w.dot(ray.direction) - w.dot(d)) / denominator;
}

std::optional<Eigen::Vector3d> rayHitOnPlane(const Ray& ray, const Eigen::Vector3d& point,
                                             const Eigen::Vector3d& normal) {
  const double facing = normal.dot(ray.direction);
  if (std::abs(facing) < 1e-12 * normal.norm()) return std::nullopt;
  const double t = normal.dot(point - ray.origin) / facing;
  if (t <= 0.0) return std::nullopt;
  return ray.origin + t * ray.direction;
}

Camera orbit(const Camera& camera, const Eigen::Vector3d& pivot, double yaw_rad, double pitch_rad) {
  // Eye, target and up turn together about the pivot: the pivot keeps its place in the camera's
  // frame, hence its pixel.
  const Eigen::Matrix3d rotation = turnRotation(axesOf(camera), yaw_rad, pitch_rad);
  Camera turned = camera;
  turned.position = pivot + rotation * (camera.position - pivot);
  turned.target = pivot + rotation * (camera.target - pivot);
  turned.up = rotation * camera.up;
  return turned;
}

Camera pan(const Camera& camera, double dx_px, double dy_px) {
  const Axes axes = axesOf(camera);
  const double scale = metresPerPixel(camera, (camera.target - camera.position).norm());
  // The world moves with the cursor: the camera moves the other way.
  const Eigen::Vector3d shift = axes.right * (-dx_px * scale) + axes.up * (dy_px * scale);
  Camera moved = camera;
  moved.position += shift;
  moved.target += shift;
  return moved;
}

Camera zoomToPoint(const Camera& camera, const Eigen::Vector3d& point, double factor) {
  assert(factor > 0.0 && "a zoom factor must be positive");
  Camera zoomed = camera;
  if (camera.projection == Projection::kPerspective) {
    // Scaling eye and target about the point keeps every direction from the eye, hence the pixel.
    zoomed.position = point + factor * (camera.position - point);
    zoomed.target = point + factor * (camera.target - point);
    return zoomed;
  }
  // Orthographic: scale the view about the point's place in the view plane.
  const Axes axes = axesOf(camera);
  const Eigen::Vector3d offset = point - camera.position;
  const Eigen::Vector3d in_plane = axes.right * offset.dot(axes.right) + axes.up * offset.dot(axes.up);
  const Eigen::Vector3d shift = (1.0 - factor) * in_plane;
  zoomed.position += shift;
  zoomed.target += shift;
  zoomed.ortho_height_m = camera.ortho_height_m * factor;
  return zoomed;
}

Camera fly(const Camera& camera, const Eigen::Vector3d& move_right_up_forward, double yaw_rad, double pitch_rad) {
  const Axes axes = axesOf(camera);
  const Eigen::Vector3d shift = axes.right * move_right_up_forward.x() + axes.up * move_right_up_forward.y() +
                                axes.forward * move_right_up_forward.z();
  const Eigen::Matrix3d rotation = turnRotation(axes, yaw_rad, pitch_rad);
  Camera flown = camera;
  flown.position += shift;
  flown.target = flown.position + rotation * (camera.target - camera.position);
  flown.up = rotation * camera.up;
  return flown;
}

}  // namespace plumb::view
