#pragma once
// The initial seed of the region grower (paper section 3.4): up to three planes in the points
// of the seed sphere, found by RANSAC and ranked by inlier count, the unstable ones optionally
// dropped by Otsu's threshold. Each plane then starts an incremental regression.

#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "reco/ransac.h"

namespace plumb::reco {

struct SeedOptions {
  double threshold = 0.01;     // plane threshold t_p, metres
  std::size_t max_planes = 3;  // a corner seed has three
  // A plane within parallel_deg of one found already (a door leaf in its recess behind the
  // wall, a shelf above the floor) does not take one of the max_planes slots, which are for
  // the differently oriented surfaces that meet at a corner; at most max_parallel such planes
  // are kept (a stair has many parallel treads: the others are left for the growth).
  double parallel_deg = 10.0;
  std::size_t max_parallel = 1;
  double min_inlier_fraction = 0.05;  // a plane needs this share of the seed points (and >= 6)
  bool drop_unstable = true;          // Otsu's threshold on the inlier counts
  std::uint64_t seed = 1;             // of the random generator: the same points give the same planes
  std::uint32_t max_iterations = 500;
  // The point the user picked: the plane it lies on (the nearest within the threshold) is never
  // dropped as unstable. Its surface may have the fewest seed points (the near face of a thin
  // wall whose far face a scanner saw closer), but it is the one the user asked for.
  std::optional<Eigen::Vector3d> picked;
};

struct SeedPlane {
  Plane plane;
  std::vector<std::uint32_t> inliers;  // indices into the seed points
};

// The seed planes of `points`, most supported first: up to max_planes of different orientations
// and max_parallel more parallel to those. Each point supports at most one plane: sequential
// RANSAC removes a plane's inliers before looking for the next.
std::vector<SeedPlane> findSeedPlanes(std::span<const Eigen::Vector3d> points, const SeedOptions& options);

}  // namespace plumb::reco
