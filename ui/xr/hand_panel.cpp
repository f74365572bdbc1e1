#include "ui/xr/hand_panel.h"

#include <Eigen/Geometry>
#include <numbers>

namespace plumb::xr {

HandPanel panelOnHand(const Pose& hand, double aspect, double width_m) {
  HandPanel panel;
  panel.width_m = width_m;
  panel.height_m = width_m / aspect;
  // The controller points forward (-z); a panel facing +z of its frame faces the user. Tilted
  // back about the hand's x so that it looks up at the eyes over the hand.
  const Eigen::Quaterniond tilt(Eigen::AngleAxisd(std::numbers::pi / 6.0, Eigen::Vector3d::UnitX()));
  panel.pose.orientation = hand.orientation * tilt;
  panel.pose.position = hand.position + hand.orientation * Eigen::Vector3d(0.0, 0.12 + 0.5 * panel.height_m, 0.0);
  return panel;
}

std::optional<Eigen::Vector2d> panelPoint(const HandPanel& panel, const Pose& aim) {
  const Eigen::Vector3d origin = aim.position;
  const Eigen::Vector3d direction = aim.orientation * Eigen::Vector3d(0.0, 0.0, -1.0);
  const Eigen::Vector3d normal = panel.pose.orientation * Eigen::Vector3d::UnitZ();
  const double facing = direction.dot(normal);
  if (facing >= -1e-9) return std::nullopt;  // parallel, or from behind
  const double t = (panel.pose.position - origin).dot(normal) / facing;
  if (t <= 0.0) return std::nullopt;
  const Eigen::Vector3d from_centre = origin + t * direction - panel.pose.position;
  const double x = from_centre.dot(panel.pose.orientation * Eigen::Vector3d::UnitX());
  const double y = from_centre.dot(panel.pose.orientation * Eigen::Vector3d::UnitY());
  const Eigen::Vector2d uv(x / panel.width_m + 0.5, 0.5 - y / panel.height_m);
  if (uv.x() < 0.0 || uv.x() > 1.0 || uv.y() < 0.0 || uv.y() > 1.0) return std::nullopt;
  return uv;
}

}  // namespace plumb::xr
