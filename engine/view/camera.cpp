#include "engine/view/camera.h"

#include <Eigen/Geometry>
#include <cassert>
#include <cmath>
#include <numbers>

#include "engine/core/error.h"

namespace plumb::view {
namespace {

bool finite(const Eigen::Vector3d& v) {
  return v.allFinite();
}

bool withinWorld(const Eigen::Vector3d& v) {
  return v.cwiseAbs().maxCoeff() <= kMaxCoordinate;
}

}  // namespace

std::optional<CameraProblem> findCameraProblem(const Camera& camera) {
  if (!finite(camera.position)) return CameraProblem{"position", "must be finite numbers"};
  if (!finite(camera.target)) return CameraProblem{"target", "must be finite numbers"};
  if (!finite(camera.up)) return CameraProblem{"up", "must be finite numbers"};
  if (!withinWorld(camera.position)) return CameraProblem{"position", "must lie within 1e12 m of the origin"};
  if (!withinWorld(camera.target)) return CameraProblem{"target", "must lie within 1e12 m of the origin"};
  const Eigen::Vector3d direction = camera.target - camera.position;
  // Subtracting two UTM coordinates can overflow only for absurd inputs, but check anyway.
  if (!finite(direction) || direction.norm() < kMinTargetDistance) {
    return CameraProblem{"target", "must lie at least 1 micrometre from the position (the camera needs a direction)"};
  }
  const double up_length = camera.up.norm();
  if (!(up_length > 0.0)) return CameraProblem{"up", "must not be the zero vector"};
  const double sine = direction.normalized().cross(camera.up / up_length).norm();
  if (sine < std::sin(kMinUpAngle)) {
    return CameraProblem{"up", "must not be parallel to the view direction (target - position)"};
  }
  if (!std::isfinite(camera.fov_deg) || camera.fov_deg < kMinFovDeg || camera.fov_deg >= 180.0) {
    return CameraProblem{"fov_deg", "must lie between 1e-6 degrees and 180 degrees (exclusive)"};
  }
  if (camera.eye_fov) {
    const EyeFov& fov = *camera.eye_fov;
    const auto side = [](double angle) { return std::isfinite(angle) && std::abs(angle) < 0.5 * std::numbers::pi; };
    if (!side(fov.left) || !side(fov.right) || !side(fov.up) || !side(fov.down)) {
      return CameraProblem{"eye_fov", "each side's angle must be finite and within 90 degrees of the view direction"};
    }
    if (!(fov.left < fov.right) || !(fov.down < fov.up)) {
      return CameraProblem{"eye_fov", "left must be less than right and down less than up"};
    }
  }
  if (!std::isfinite(camera.ortho_height_m) || camera.ortho_height_m < kMinExtent) {
    return CameraProblem{"ortho_height_m", "must be at least 1 micrometre"};
  }
  if (camera.viewport_width_px <= 0 || camera.viewport_height_px <= 0) {
    return CameraProblem{"viewport", "width and height must be positive pixel counts"};
  }
  if (!std::isfinite(camera.near_m) || camera.near_m < kMinExtent) {
    return CameraProblem{"near_m", "must be at least 1 micrometre"};
  }
  if (!std::isfinite(camera.far_m) || camera.far_m <= camera.near_m || camera.far_m > kMaxFar) {
    return CameraProblem{"far_m", "must be greater than near_m and at most 1e12 m"};
  }
  return std::nullopt;
}

void validateCamera(const Camera& camera) {
  if (const auto problem = findCameraProblem(camera)) {
    throw Error("camera: field '" + problem->field + "': " + problem->what);
  }
}

Eigen::Vector3d viewDirection(const Camera& camera) {
  return (camera.target - camera.position).normalized();
}

double aspectRatio(const Camera& camera) {
  return static_cast<double>(camera.viewport_width_px) / static_cast<double>(camera.viewport_height_px);
}

Eigen::Matrix4d viewMatrix(const Camera& camera) {
  assert(!findCameraProblem(camera) && "validate the camera (validateCamera) before building its matrices");
  // The rows of the rotation are the camera axes in world coordinates: right, up, backwards
  // (the camera looks down -z), as gluLookAt builds them.
  const Eigen::Vector3d forward = viewDirection(camera);
  const Eigen::Vector3d right = forward.cross(camera.up).normalized();
  const Eigen::Vector3d up = right.cross(forward);
  Eigen::Matrix4d view = Eigen::Matrix4d::Identity();
  view.block<1, 3>(0, 0) = right.transpose();
  view.block<1, 3>(1, 0) = up.transpose();
  view.block<1, 3>(2, 0) = -forward.transpose();
  view.block<3, 1>(0, 3) = -(view.block<3, 3>(0, 0) * camera.position);
  return view;
}

double metresPerPixel(const Camera& camera, double depth) {
  if (camera.projection == Projection::kOrthographic) return camera.ortho_height_m / camera.viewport_height_px;
  if (camera.eye_fov) {
    return depth * (std::tan(camera.eye_fov->up) - std::tan(camera.eye_fov->down)) / camera.viewport_height_px;
  }
  return 2.0 * depth * std::tan(camera.fov_deg * std::numbers::pi / 360.0) / camera.viewport_height_px;
}

Eigen::Matrix4d projectionMatrix(const Camera& camera) {
  assert(!findCameraProblem(camera) && "validate the camera (validateCamera) before building its matrices");
  const double aspect = aspectRatio(camera);
  const double near = camera.near_m;
  const double far = camera.far_m;
  Eigen::Matrix4d projection = Eigen::Matrix4d::Zero();
  if (camera.projection == Projection::kPerspective && camera.eye_fov) {
    // glFrustum with the sides at near * tan(angle).
    const double left = std::tan(camera.eye_fov->left), right = std::tan(camera.eye_fov->right);
    const double up = std::tan(camera.eye_fov->up), down = std::tan(camera.eye_fov->down);
    projection(0, 0) = 2.0 / (right - left);
    projection(0, 2) = (right + left) / (right - left);
    projection(1, 1) = 2.0 / (up - down);
    projection(1, 2) = (up + down) / (up - down);
    projection(2, 2) = (far + near) / (near - far);
    projection(2, 3) = 2.0 * far * near / (near - far);
    projection(3, 2) = -1.0;
  } else if (camera.projection == Projection::kPerspective) {
    // gluPerspective.
    const double f = 1.0 / std::tan(camera.fov_deg * std::numbers::pi / 360.0);
    projection(0, 0) = f / aspect;
    projection(1, 1) = f;
    projection(2, 2) = (far + near) / (near - far);
    projection(2, 3) = 2.0 * far * near / (near - far);
    projection(3, 2) = -1.0;
  } else {
    // glOrtho with a symmetric box of ortho_height_m by ortho_height_m * aspect.
    const double height = camera.ortho_height_m;
    projection(0, 0) = 2.0 / (height * aspect);
    projection(1, 1) = 2.0 / height;
    projection(2, 2) = -2.0 / (far - near);
    projection(2, 3) = -(far + near) / (far - near);
    projection(3, 3) = 1.0;
  }
  return projection;
}

}  // namespace plumb::view
