// Seed planes, paper section 3.4.
//
//   1. Candidates: all seed points.
//   2. RANSAC the best plane among the candidates (threshold t_p); stop when none has the
//      minimum support or max_planes are found. A plane parallel to one found already counts
//      apart (max_parallel): at a click on a wall 0.3 m above the floor beside a recessed door,
//      the door leaf 0.12 m behind the wall outweighed the floor and took the third slot, and
//      the corner was lost.
//   3. Remove its inliers from the candidates and repeat.
//   4. Rank by inlier count; with drop_unstable, keep only Otsu's high class of the counts, and
//      the plane of the picked point.

#include "reco/seed_planes.h"

#include <algorithm>
#include <cmath>

#include "reco/otsu.h"

namespace plumb::reco {

std::vector<SeedPlane> findSeedPlanes(std::span<const Eigen::Vector3d> points, const SeedOptions& options) {
  const PlaneSampleModel model(points);
  Random random(options.seed);
  RansacOptions ransac;
  ransac.threshold = options.threshold;
  ransac.max_iterations = options.max_iterations;
  ransac.min_inliers = std::max<std::size_t>(
      6, static_cast<std::size_t>(std::ceil(options.min_inlier_fraction * static_cast<double>(points.size()))));

  std::vector<std::uint32_t> candidates(points.size());
  for (std::uint32_t i = 0; i < candidates.size(); ++i) candidates[i] = i;

  const double parallel_cos = std::cos(options.parallel_deg * M_PI / 180.0);
  const auto parallelToOneFound = [&](const Plane& plane, const std::vector<SeedPlane>& found) {
    return std::any_of(found.begin(), found.end(), [&](const SeedPlane& other) {
      return std::abs(other.plane.normal.dot(plane.normal)) >= parallel_cos;
    });
  };
  std::vector<SeedPlane> planes;
  std::size_t oriented = 0, parallel = 0;
  while (oriented < options.max_planes) {
    auto found = ransacPlane(model, candidates, ransac, random);
    if (!found) break;
    const bool parallel_one = parallelToOneFound(found->plane, planes);
    const bool keep = !parallel_one || parallel < options.max_parallel;
    if (keep) ++(parallel_one ? parallel : oriented);
    // Candidates stay sorted: remove the (sorted) inliers by a merge.
    std::vector<std::uint32_t> rest;
    rest.reserve(candidates.size() - found->inliers.size());
    std::set_difference(candidates.begin(), candidates.end(), found->inliers.begin(), found->inliers.end(),
                        std::back_inserter(rest));
    candidates = std::move(rest);
    // A parallel plane past max_parallel is dropped, its points with it: the search goes on.
    if (keep) planes.push_back({found->plane, std::move(found->inliers)});
  }

  std::stable_sort(planes.begin(), planes.end(),
                   [](const SeedPlane& a, const SeedPlane& b) { return a.inliers.size() > b.inliers.size(); });
  if (options.drop_unstable) {
    std::vector<double> counts;
    for (const SeedPlane& plane : planes) counts.push_back(static_cast<double>(plane.inliers.size()));
    const std::size_t kept = otsuHighClassSize(counts);
    std::optional<std::size_t> picked;
    if (options.picked) {
      double nearest = options.threshold;
      for (std::size_t i = 0; i < planes.size(); ++i) {
        const double d = planes[i].plane.distance(*options.picked);
        if (d < nearest) {
          nearest = d;
          picked = i;
        }
      }
    }
    if (picked && *picked >= kept) std::swap(planes[kept], planes[*picked]);  // the picked plane stays
    planes.resize(picked && *picked >= kept ? kept + 1 : kept);
  }
  return planes;
}

}  // namespace plumb::reco
