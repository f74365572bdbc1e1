#include "reco/sim/scene.h"

#include <cmath>
#include <numbers>

namespace plumb::reco::sim {

Eigen::Vector3d SceneFrame::rotate(const Eigen::Vector3d& local) const {
  const double angle = rotation_deg * std::numbers::pi / 180.0;
  const double c = std::cos(angle), s = std::sin(angle);
  return {c * local.x() - s * local.y(), s * local.x() + c * local.y(), local.z()};
}

TruthPlane SceneFrame::toWorld(const TruthPlane& plane) const {
  // A point x on the local plane maps to y = R x + o; n.x + d = 0 becomes (R n).y + d - (R n).o = 0.
  TruthPlane world = plane;
  world.normal = rotate(plane.normal);
  world.offset = plane.offset - world.normal.dot(offset);
  return world;
}

}  // namespace plumb::reco::sim
