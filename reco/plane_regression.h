#pragma once
// Incremental plane regression: paper section 3.2 and appendix A.
//
// Keeps the sums S (coordinates), Sq (squares) and D (cross products yz, xz, xy) and the count c
// of the points added so far, so that adding a point and merging two regressions are O(1) and
// no point is stored. The sums are taken relative to a reference point (by default the first
// added point): at UTM coordinates (x ~ 5e5, y ~ 5e6) the squares of raw coordinates cancel
// catastrophically in the covariance, relative ones do not (tests/reco/plane_regression_test).
//
// A value type; not thread-safe, copy it to hand it to another thread.

#include <Eigen/Core>
#include <cstdint>

#include "reco/plane.h"

namespace plumb::reco {

class PlaneRegression {
 public:
  // An empty regression whose reference becomes the first point added.
  PlaneRegression() = default;

  // An empty regression with a fixed reference point. withReference(Zero()) gives the raw,
  // unrebased sums of the paper's equation 1, kept for the tests that show why rebasing matters.
  static PlaneRegression withReference(const Eigen::Vector3d& reference);

  // Adds one point (world coordinates). O(1). The point must be finite.
  void add(const Eigen::Vector3d& point);

  // Adds all points of `other`, as if they had been added one by one. O(1).
  void merge(const PlaneRegression& other);

  // Re-expresses the sums relative to `new_reference` (appendix A). Changes no result but the
  // rounding: rebase near the points before the sums grow large.
  void rebase(const Eigen::Vector3d& new_reference);

  std::uint64_t count() const { return count_; }
  bool empty() const { return count_ == 0; }
  const Eigen::Vector3d& reference() const { return reference_; }

  // Mean of the points, world coordinates. Requires count() > 0.
  Eigen::Vector3d centroid() const;

  // Sample covariance (divided by c - 1) in m^2. Requires count() >= 2.
  Eigen::Matrix3d covariance() const;

  // Plane synthesis (section 3.3) by eigen decomposition of the covariance. Never NaN: degenerate
  // input gives a Plane with valid == false.
  Plane fit() const;

  // The sums relative to reference(), as defined in equation 1.
  const Eigen::Vector3d& sum() const { return sum_; }
  const Eigen::Vector3d& sumSquares() const { return sum_squares_; }
  const Eigen::Vector3d& sumCross() const { return sum_cross_; }

 private:
  Eigen::Vector3d reference_ = Eigen::Vector3d::Zero();
  bool reference_fixed_ = false;
  Eigen::Vector3d sum_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d sum_squares_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d sum_cross_ = Eigen::Vector3d::Zero();  // (yz, xz, xy)
  std::uint64_t count_ = 0;
};

// Plane synthesis (section 3.3) from a centroid and a sample covariance (divided by count - 1):
// the normal is the eigenvector of the smallest eigenvalue. Never NaN: fewer than 3 points, or
// points on a line, give a Plane with valid == false. PlaneRegression::fit and the weighted fit
// (robust_plane_fit.h) both end here.
Plane synthesizePlane(const Eigen::Vector3d& centroid, const Eigen::Matrix3d& covariance, std::uint64_t count);

}  // namespace plumb::reco
