// Tukey's biweight, a robust scale and the weighted plane fit of robust_plane_fit.h.

#include "reco/robust_plane_fit.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstdint>

#include "reco/plane_regression.h"

namespace plumb::reco {

double biweight(double residual, double window) {
  const double u = residual / window;
  if (!(std::abs(u) < 1.0)) return 0.0;
  const double v = 1.0 - u * u;
  return v * v;
}

double robustScale(std::vector<double> absolute_residuals) {
  if (absolute_residuals.empty()) return 0.0;
  // 1 / Phi^-1(3/4): the median of |x| for a standard normal x is 0.6745.
  constexpr double kNormalConsistency = 1.4826;
  const auto middle = absolute_residuals.begin() + static_cast<std::ptrdiff_t>(absolute_residuals.size() / 2);
  std::nth_element(absolute_residuals.begin(), middle, absolute_residuals.end());
  return kNormalConsistency * *middle;
}

Plane fitWeightedPlane(std::span<const Eigen::Vector3d> points, std::span<const double> weights) {
  assert(points.size() == weights.size());
  if (points.empty()) return {};
  const Eigen::Vector3d reference = points.front();
  double total = 0.0;
  std::uint64_t count = 0;
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (!(weights[i] > 0.0)) continue;
    total += weights[i];
    sum += weights[i] * (points[i] - reference);
    ++count;
  }
  if (count < 3) return {};
  const Eigen::Vector3d mean = sum / total;
  Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (!(weights[i] > 0.0)) continue;
    const Eigen::Vector3d q = points[i] - reference - mean;
    scatter.noalias() += weights[i] * q * q.transpose();
  }
  // Scaled as a sample covariance of `count` points, so that lambda2 and rms read as
  // PlaneRegression's do.
  const double n = static_cast<double>(count);
  const Eigen::Matrix3d covariance = scatter / total * (n / (n - 1.0));
  return synthesizePlane(reference + mean, covariance, count);
}

}  // namespace plumb::reco
