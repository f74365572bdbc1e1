// RANSAC for one plane.
//
//   1. Draw three distinct candidates; skip degenerate (collinear) samples.
//   2. Score the hypothesis on the candidates (RansacScore); keep the best.
//   3. Stop after N = log(1 - confidence) / log(1 - w^3) iterations, w the best inlier ratio so
//      far (at most max_iterations).
//   4. Refit the best hypothesis's inliers by least squares and select the inliers of the refit
//      plane (the refit is more accurate than any three-point plane).

#include "reco/ransac.h"

#include <cmath>

namespace plumb::reco {
namespace {

std::uint32_t iterationsNeeded(double inlier_ratio, double confidence, std::uint32_t max_iterations) {
  const double all_inliers = std::pow(inlier_ratio, PlaneSampleModel::kSampleSize);
  if (all_inliers >= 1.0) return 1;
  if (all_inliers <= 0.0) return max_iterations;
  const double needed = std::log(1.0 - confidence) / std::log(1.0 - all_inliers);
  return needed >= max_iterations ? max_iterations : static_cast<std::uint32_t>(std::ceil(needed));
}

}  // namespace

std::optional<RansacResult> ransacPlane(const PlaneSampleModel& model, std::span<const std::uint32_t> candidates,
                                        const RansacOptions& options, Random& random) {
  const std::size_t n = candidates.size();
  if (n < static_cast<std::size_t>(PlaneSampleModel::kSampleSize) || n < options.min_inliers) return std::nullopt;

  std::optional<PlaneHypothesis> best;
  std::size_t best_count = 0;
  double best_cost = INFINITY;
  std::uint32_t iterations = 0;
  std::uint32_t needed = options.max_iterations;
  while (iterations < needed) {
    ++iterations;
    std::array<std::uint32_t, 3> sample{};
    sample[0] = candidates[random.below(n)];
    do sample[1] = candidates[random.below(n)];
    while (sample[1] == sample[0]);
    do sample[2] = candidates[random.below(n)];
    while (sample[2] == sample[0] || sample[2] == sample[1]);

    const auto hypothesis = model.fromSample(sample);
    if (!hypothesis) continue;
    const PlaneSampleModel::Support support = model.support(*hypothesis, options.threshold, candidates);
    const bool better =
        options.score == RansacScore::kInlierCount ? support.inliers > best_count : support.cost < best_cost;
    if (better) {
      best_count = support.inliers;
      best_cost = support.cost;
      best = hypothesis;
      // The stopping rule reads the inlier ratio of the best hypothesis (under MSAC, not always
      // the largest seen: a slightly conservative estimate of w).
      needed = iterationsNeeded(static_cast<double>(support.inliers) / static_cast<double>(n), options.confidence,
                                options.max_iterations);
    }
  }
  if (!best || best_count < options.min_inliers) return std::nullopt;

  RansacResult result;
  result.iterations = iterations;
  model.selectInliers(*best, options.threshold, candidates, result.inliers);
  result.plane = model.refit(result.inliers);
  if (!result.plane.valid) return std::nullopt;
  const PlaneHypothesis refit{result.plane.normal, result.plane.centroid};
  model.selectInliers(refit, options.threshold, candidates, result.inliers);
  if (result.inliers.size() < options.min_inliers) return std::nullopt;
  return result;
}

}  // namespace plumb::reco
