#pragma once
// The RANSAC estimator (Fischler and Bolles 1981; the adaptive stopping rule of Hartley and
// Zisserman) over a PlaneSampleModel: the best-supported plane among the candidate points.
// "Best" is MSAC's (Torr and Zisserman 2000) by default: the least sum of truncated squared
// distances, which, unlike a count of inliers, prefers the plane whose inliers lie close to it.
// Where the noise is a good part of the threshold that matters: a plane slanted across a corner
// gathers the strips of two walls along their edge, spread evenly over the whole window, and
// may outnumber what is left of a wall in a small seed sphere; it cannot outscore it.

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "engine/core/random.h"
#include "reco/plane_sample_model.h"

namespace plumb::reco {

enum class RansacScore {
  kInlierCount,       // the classic: most inliers
  kTruncatedSquares,  // MSAC: least sum of min(d^2, threshold^2)
};

struct RansacOptions {
  double threshold = 0.01;  // inlier distance, metres
  RansacScore score = RansacScore::kTruncatedSquares;
  double confidence = 0.99;  // probability of having drawn one all-inlier sample at the end
  std::uint32_t max_iterations = 1000;
  std::size_t min_inliers = 3;  // a plane with fewer inliers is no plane
};

struct RansacResult {
  Plane plane;                         // least-squares refit of the inliers
  std::vector<std::uint32_t> inliers;  // within the threshold of the refitted plane
  std::uint32_t iterations = 0;
};

// The plane supported by most of `candidates` (indices into the model's points). `random` is
// the caller's seeded generator: the result is reproducible for a seed. None when no sample
// gives a plane with min_inliers inliers.
std::optional<RansacResult> ransacPlane(const PlaneSampleModel& model, std::span<const std::uint32_t> candidates,
                                        const RansacOptions& options, Random& random);

}  // namespace plumb::reco
