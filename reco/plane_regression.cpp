// Incremental plane regression and plane synthesis.
// Paper: "Feature-assisted interactive geometry reconstruction in 3D point clouds using
// incremental region growing", section 3.2 (equations 1 to 3), section 3.3 and appendix A.
//
//   1. add:    S += q, Sq += q*q, D += (qy qz, qx qz, qx qy), c += 1, with q = p - reference.
//   2. rebase: appendix A, d = old reference - new reference.
//   3. merge:  rebase the other regression's sums onto this reference, then add the sums.
//   4. covariance (equation 3) from the sums; translation-invariant, so relative sums suffice.
//   5. fit:    eigen decomposition (synthesizePlane); normal = eigenvector of the smallest eigenvalue.
//
// Appendix A prints the cross-term update with its components in the order (xy, xz, yz) while
// D is defined as (yz, xz, xy); the code follows the definition of D.

#include "reco/plane_regression.h"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <algorithm>
#include <cassert>
#include <cmath>

namespace plumb::reco {
namespace {

// The middle eigenvalue must exceed this fraction of the largest: below it the points lie on a
// line (or are one point) and no plane is defined. 1e-12 still accepts a 1 km x 1 mm strip.
constexpr double kMinSpreadRatio = 1e-12;

struct Sums {
  Eigen::Vector3d sum, squares, cross;
};

// Appendix A: the sums of the points relative to reference r0 re-expressed relative to r,
// with d = r0 - r.
Sums rebased(const Sums& sums, std::uint64_t count, const Eigen::Vector3d& d) {
  const double c = static_cast<double>(count);
  const Eigen::Vector3d& s = sums.sum;
  Sums out;
  out.sum = s + c * d;
  out.squares = sums.squares + 2.0 * d.cwiseProduct(s) + c * d.cwiseProduct(d);
  out.cross = sums.cross + Eigen::Vector3d(d.y() * s.z() + d.z() * s.y() + c * d.y() * d.z(),
                                           d.x() * s.z() + d.z() * s.x() + c * d.x() * d.z(),
                                           d.x() * s.y() + d.y() * s.x() + c * d.x() * d.y());
  return out;
}

}  // namespace

PlaneRegression PlaneRegression::withReference(const Eigen::Vector3d& reference) {
  PlaneRegression regression;
  regression.reference_ = reference;
  regression.reference_fixed_ = true;
  return regression;
}

void PlaneRegression::add(const Eigen::Vector3d& point) {
  assert(point.allFinite() && "PlaneRegression::add takes finite points; filter NaN on input");
  if (count_ == 0 && !reference_fixed_) {
    reference_ = point;
    reference_fixed_ = true;
  }
  const Eigen::Vector3d q = point - reference_;
  sum_ += q;
  sum_squares_ += q.cwiseProduct(q);
  sum_cross_ += Eigen::Vector3d(q.y() * q.z(), q.x() * q.z(), q.x() * q.y());
  ++count_;
}

void PlaneRegression::merge(const PlaneRegression& other) {
  if (other.count_ == 0) return;
  if (count_ == 0 && !reference_fixed_) {
    *this = other;
    return;
  }
  const Sums moved =
      rebased({other.sum_, other.sum_squares_, other.sum_cross_}, other.count_, other.reference_ - reference_);
  sum_ += moved.sum;
  sum_squares_ += moved.squares;
  sum_cross_ += moved.cross;
  count_ += other.count_;
}

void PlaneRegression::rebase(const Eigen::Vector3d& new_reference) {
  const Sums moved = rebased({sum_, sum_squares_, sum_cross_}, count_, reference_ - new_reference);
  sum_ = moved.sum;
  sum_squares_ = moved.squares;
  sum_cross_ = moved.cross;
  reference_ = new_reference;
  reference_fixed_ = true;
}

Eigen::Vector3d PlaneRegression::centroid() const {
  assert(count_ > 0 && "centroid of an empty regression");
  return reference_ + sum_ / static_cast<double>(count_);
}

Eigen::Matrix3d PlaneRegression::covariance() const {
  assert(count_ >= 2 && "covariance needs at least two points");
  const double c = static_cast<double>(count_);
  const Eigen::Vector3d mean = sum_ / c;
  Eigen::Matrix3d cov;
  cov(0, 0) = sum_squares_.x() - mean.x() * sum_.x();
  cov(1, 1) = sum_squares_.y() - mean.y() * sum_.y();
  cov(2, 2) = sum_squares_.z() - mean.z() * sum_.z();
  cov(0, 1) = cov(1, 0) = sum_cross_.z() - mean.x() * sum_.y();
  cov(0, 2) = cov(2, 0) = sum_cross_.y() - mean.x() * sum_.z();
  cov(1, 2) = cov(2, 1) = sum_cross_.x() - mean.y() * sum_.z();
  return cov / (c - 1.0);
}

Plane PlaneRegression::fit() const {
  if (count_ < 3) return {};
  return synthesizePlane(centroid(), covariance(), count_);
}

Plane synthesizePlane(const Eigen::Vector3d& centroid, const Eigen::Matrix3d& covariance, std::uint64_t count) {
  if (count < 3 || !covariance.allFinite() || !centroid.allFinite()) return {};

  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(covariance);
  if (solver.info() != Eigen::Success) return {};
  // Eigen sorts ascending; the paper numbers them descending.
  const Eigen::Vector3d& values = solver.eigenvalues();
  const double lambda0 = values(2);
  const double lambda1 = values(1);
  if (!(lambda1 > kMinSpreadRatio * lambda0)) return {};  // also rejects NaN and all-equal points

  Plane plane;
  plane.valid = true;
  plane.lambda0 = lambda0;
  plane.lambda1 = lambda1;
  // Rounding can push the smallest eigenvalue of a perfect plane slightly below zero.
  plane.lambda2 = std::max(values(0), 0.0);
  plane.normal = solver.eigenvectors().col(0).normalized();
  plane.tangent = solver.eigenvectors().col(2).normalized();
  plane.bitangent = plane.normal.cross(plane.tangent);
  plane.centroid = centroid;
  plane.offset = -plane.normal.dot(plane.centroid);
  plane.point_count = count;
  const double c = static_cast<double>(count);
  plane.rms = std::sqrt(plane.lambda2 * (c - 1.0) / c);
  return plane;
}

}  // namespace plumb::reco
