#pragma once
// A plane synthesised from a plane regression (paper section 3.3).

#include <Eigen/Core>
#include <cmath>
#include <cstdint>

namespace plumb::reco {

struct Plane {
  // False for degenerate input (fewer than 3 points, all on a line, all the same point or
  // non-finite sums); every other field is then zero and must not be used.
  bool valid = false;

  // Unit normal: the eigenvector of the smallest eigenvalue. Unsigned as in the paper: its sign
  // is whatever the decomposition gives; orient it with orientedTowards() where it matters.
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();
  // Unit directions of the largest and middle spread; (tangent, bitangent, normal) is right-handed.
  Eigen::Vector3d tangent = Eigen::Vector3d::Zero();
  Eigen::Vector3d bitangent = Eigen::Vector3d::Zero();

  // The centroid of the points, in world coordinates: the least-squares plane passes through it.
  // (The paper takes the last added point as the origin; that point is off the plane by up to
  // the plane threshold, the centroid is not.)
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  // d in normal . x + d = 0.
  double offset = 0.0;

  // Eigenvalues of the sample covariance in m^2, lambda0 >= lambda1 >= lambda2 >= 0.
  // lambda2 is the regression variance of the paper: the variance along the normal.
  double lambda0 = 0.0;
  double lambda1 = 0.0;
  double lambda2 = 0.0;

  std::uint64_t point_count = 0;
  // Root-mean-square distance of the regression's points to this plane, in metres.
  double rms = 0.0;

  double signedDistance(const Eigen::Vector3d& point) const { return normal.dot(point - centroid); }
  double distance(const Eigen::Vector3d& point) const { return std::abs(signedDistance(point)); }

  // The same plane with its normal (and bitangent) flipped if needed so that `viewpoint` lies on
  // the positive side.
  Plane orientedTowards(const Eigen::Vector3d& viewpoint) const {
    Plane oriented = *this;
    if (signedDistance(viewpoint) < 0.0) {
      oriented.normal = -normal;
      oriented.bitangent = -bitangent;
      oriented.offset = -offset;
    }
    return oriented;
  }
};

}  // namespace plumb::reco
