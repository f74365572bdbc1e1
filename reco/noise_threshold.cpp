// t_p from the data (noise_threshold.h).

#include "reco/noise_threshold.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <vector>

#include "reco/grid_index.h"

namespace plumb::reco {
namespace {

double normalCdf(double x) {
  return 0.5 * std::erfc(-x / std::sqrt(2.0));
}

// Phi^-1(p) for p in (0, 1), by bisection: 60 halvings of [-10, 10] reach double precision.
double normalQuantile(double p) {
  double low = -10.0, high = 10.0;
  for (int i = 0; i < 60; ++i) {
    const double middle = 0.5 * (low + high);
    (normalCdf(middle) < p ? low : high) = middle;
  }
  return 0.5 * (low + high);
}

// The median of |x| for a standard normal x cut off at +-k.
double truncatedMedianAbs(double k) {
  return normalQuantile(0.25 + 0.5 * normalCdf(k));
}

}  // namespace

double truncatedNormalSigma(std::span<const double> abs_residuals, double window) {
  if (abs_residuals.empty() || !(window > 0.0)) return 0.0;
  std::vector<double> values(abs_residuals.begin(), abs_residuals.end());
  const auto middle = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
  std::nth_element(values.begin(), middle, values.end());
  const double m = *middle;
  if (m <= 0.0) return 0.0;
  // sigma * q(window / sigma) grows with sigma, from 0 towards window / 2 (a flat distribution
  // over the window): bisect between the untruncated estimate and the cap.
  const double cap = 8.0 * window;
  if (cap * truncatedMedianAbs(window / cap) <= m) return cap;
  double low = m / truncatedMedianAbs(INFINITY), high = cap;
  for (int i = 0; i < 60; ++i) {
    const double sigma = 0.5 * (low + high);
    (sigma * truncatedMedianAbs(window / sigma) < m ? low : high) = sigma;
  }
  return 0.5 * (low + high);
}

double localNoiseSigma(std::span<const Eigen::Vector3d> points, double radius) {
  constexpr std::size_t kSamples = 64;
  constexpr std::size_t kMinPatch = 12;
  if (points.empty()) return 0.0;
  const std::size_t stride = std::max<std::size_t>(1, points.size() / kSamples);
  // A grid of step `radius`: a patch is in the 27 grid cells around its centre (a full-detail
  // seed sphere holds hundreds of thousands of points; scanning all of them per patch cost more
  // than the rest of the seed).
  const PointGrid grid(points.front(), radius);
  const GridIndex index(grid, points);
  std::vector<double> sigmas;
  for (std::size_t s = 0; s < points.size(); s += stride) {
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    Eigen::Matrix3d outer = Eigen::Matrix3d::Zero();
    std::size_t n = 0;
    grid.forEachAround(points[s], [&](const GridKey& key) {
      for (std::uint32_t i : index.at(key)) {
        const Eigen::Vector3d d = points[i] - points[s];  // relative: UTM coordinates keep their precision
        if (d.squaredNorm() > radius * radius) continue;
        sum += d;
        outer += d * d.transpose();
        ++n;
      }
    });
    if (n < kMinPatch) continue;
    const double count = static_cast<double>(n);
    const Eigen::Matrix3d covariance = outer / count - (sum / count) * (sum / count).transpose();
    const double smallest =
        Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(covariance, Eigen::EigenvaluesOnly).eigenvalues()(0);
    sigmas.push_back(std::sqrt(std::max(smallest, 0.0) * count / (count - 3.0)));
  }
  if (sigmas.empty()) return 0.0;
  const auto middle = sigmas.begin() + static_cast<std::ptrdiff_t>(sigmas.size() / 2);
  std::nth_element(sigmas.begin(), middle, sigmas.end());
  return *middle;
}

double robustNoiseSigma(std::span<const double> abs_residuals, double window) {
  double sigma = truncatedNormalSigma(abs_residuals, window);
  std::vector<double> inner;
  for (int round = 0; round < 8 && sigma > 0.0; ++round) {
    const double inner_window = std::min(window, 2.0 * sigma);
    inner.clear();
    for (double r : abs_residuals) {
      if (r <= inner_window) inner.push_back(r);
    }
    const double next = truncatedNormalSigma(inner, inner_window);
    const bool settled = std::abs(next - sigma) < 0.01 * sigma;
    sigma = next;
    if (settled) break;
  }
  return sigma;
}

double thresholdForNoise(double sigma) {
  return std::clamp(kThresholdSigmas * sigma, kMinThreshold, kMaxThreshold);
}

}  // namespace plumb::reco
