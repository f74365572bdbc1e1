#include "engine/view/view_presets.h"

#include <algorithm>
#include <cmath>

namespace plumb::view {

namespace {
constexpr double kMargin = 1.05;  // a little room around the box
}

std::optional<ViewPreset> viewPresetNamed(std::string_view name) {
  if (name == "top") return ViewPreset::kTop;
  if (name == "front") return ViewPreset::kFront;
  if (name == "side") return ViewPreset::kSide;
  if (name == "iso") return ViewPreset::kIso;
  return std::nullopt;
}

Camera presetCamera(ViewPreset preset, const Eigen::Vector3d& min, const Eigen::Vector3d& max, int width_px,
                    int height_px) {
  const Eigen::Vector3d extent = (max - min).cwiseMax(Eigen::Vector3d::Constant(1e-3));
  const Eigen::Vector3d centre = 0.5 * (min + max);
  const double radius = 0.5 * extent.norm();
  Camera camera;
  camera.viewport_width_px = width_px;
  camera.viewport_height_px = height_px;
  camera.target = centre;
  const double aspect = static_cast<double>(width_px) / height_px;

  // Orthographic: look along `direction` from outside the box; the screen shows `across` (x) by
  // `upward` (y) of the box.
  auto orthographic = [&](const Eigen::Vector3d& direction, const Eigen::Vector3d& up, double across, double upward) {
    camera.projection = Projection::kOrthographic;
    camera.up = up;
    camera.position = centre - direction * (radius + 1.0);
    camera.ortho_height_m = kMargin * std::max(upward, across / aspect);
    camera.near_m = 0.05;
    camera.far_m = 2.0 * radius + 2.0;
  };
  switch (preset) {
    case ViewPreset::kTop:
      orthographic({0.0, 0.0, -1.0}, {0.0, 1.0, 0.0}, extent.x(), extent.y());
      break;
    case ViewPreset::kFront:
      orthographic({0.0, 1.0, 0.0}, {0.0, 0.0, 1.0}, extent.x(), extent.z());
      break;
    case ViewPreset::kSide:
      orthographic({-1.0, 0.0, 0.0}, {0.0, 0.0, 1.0}, extent.y(), extent.z());
      break;
    case ViewPreset::kIso: {
      camera.projection = Projection::kPerspective;
      camera.up = {0.0, 0.0, 1.0};
      // The sphere fits the narrower of the two fields of view.
      const double half_fov = 0.5 * camera.fov_deg * M_PI / 180.0;
      const double half_narrow = aspect >= 1.0 ? half_fov : std::atan(std::tan(half_fov) * aspect);
      const double distance = kMargin * radius / std::sin(half_narrow);
      camera.position = centre + Eigen::Vector3d(1.0, -1.0, 1.0).normalized() * distance;
      camera.near_m = std::max(1e-3, 0.01 * (distance - radius));
      camera.far_m = distance + 2.0 * radius;
      break;
    }
  }
  return camera;
}

}  // namespace plumb::view
