#include "reco/plane_sample_model.h"

#include <Eigen/Geometry>

#include "reco/plane_regression.h"

namespace plumb::reco {

std::optional<PlaneHypothesis> PlaneSampleModel::fromSample(const std::array<std::uint32_t, 3>& sample,
                                                            double min_area) const {
  const Eigen::Vector3d& a = points_[sample[0]];
  // Differences first: at UTM coordinates the cross product of raw positions would cancel.
  const Eigen::Vector3d ab = points_[sample[1]] - a;
  const Eigen::Vector3d ac = points_[sample[2]] - a;
  const Eigen::Vector3d normal = ab.cross(ac);
  const double twice_area = normal.norm();
  if (!(twice_area >= 2.0 * min_area)) return std::nullopt;
  return PlaneHypothesis{normal / twice_area, a};
}

void PlaneSampleModel::selectInliers(const PlaneHypothesis& plane, double threshold,
                                     std::span<const std::uint32_t> candidates,
                                     std::vector<std::uint32_t>& inliers) const {
  inliers.clear();
  for (std::uint32_t i : candidates) {
    if (plane.distance(points_[i]) <= threshold) inliers.push_back(i);
  }
}

PlaneSampleModel::Support PlaneSampleModel::support(const PlaneHypothesis& plane, double threshold,
                                                    std::span<const std::uint32_t> candidates) const {
  Support result;
  const double threshold2 = threshold * threshold;
  for (std::uint32_t i : candidates) {
    const double d = plane.distance(points_[i]);
    if (d <= threshold) {
      ++result.inliers;
      result.cost += d * d;
    } else {
      result.cost += threshold2;
    }
  }
  return result;
}

Plane PlaneSampleModel::refit(std::span<const std::uint32_t> inliers) const {
  PlaneRegression regression;
  for (std::uint32_t i : inliers) regression.add(points_[i]);
  return regression.fit();
}

}  // namespace plumb::reco
