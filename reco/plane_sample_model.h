#pragma once
// The plane model of RANSAC (after PCL's SampleConsensusModelPlane): a hypothesis from a minimal
// sample of three points, point-to-plane distances, inlier selection, and a least-squares refit
// through the incremental plane regression. The estimator (ransac.h) drives it.
//
// Holds a view of the points; cheap to copy; const members are thread-safe.

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "reco/plane.h"

namespace plumb::reco {

// An oriented plane normal . x + offset = 0 with a unit normal, relative to `reference` (a point
// near the data), so that distances stay exact at UTM coordinates.
struct PlaneHypothesis {
  Eigen::Vector3d normal;
  Eigen::Vector3d point;  // a point on the plane
  double distance(const Eigen::Vector3d& p) const { return std::abs(normal.dot(p - point)); }
};

class PlaneSampleModel {
 public:
  static constexpr int kSampleSize = 3;

  // `points` must outlive the model.
  explicit PlaneSampleModel(std::span<const Eigen::Vector3d> points) : points_(points) {}

  std::size_t size() const { return points_.size(); }
  const Eigen::Vector3d& point(std::uint32_t i) const { return points_[i]; }

  // The plane through three points; none when they are (nearly) collinear or coincide: the
  // triangle's area must be at least `min_area` (m^2).
  std::optional<PlaneHypothesis> fromSample(const std::array<std::uint32_t, 3>& sample, double min_area = 1e-12) const;

  // The candidates within `threshold` of the plane, appended to `inliers` (cleared first).
  void selectInliers(const PlaneHypothesis& plane, double threshold, std::span<const std::uint32_t> candidates,
                     std::vector<std::uint32_t>& inliers) const;
  // How well the plane explains the candidates: its inliers, and the MSAC cost (Torr and
  // Zisserman 2000), the sum over all candidates of min(d^2, threshold^2).
  struct Support {
    std::size_t inliers = 0;
    double cost = 0.0;
  };
  Support support(const PlaneHypothesis& plane, double threshold, std::span<const std::uint32_t> candidates) const;

  // The least-squares plane of `inliers` (section 3.2 regression; invalid for degenerate sets).
  Plane refit(std::span<const std::uint32_t> inliers) const;

 private:
  std::span<const Eigen::Vector3d> points_;
};

}  // namespace plumb::reco
