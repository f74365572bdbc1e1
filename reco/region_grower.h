#pragma once
// The interactive region growing loop (paper section 3.5) on an out-of-core octree: from the
// seed planes around a picked point, add the neighbouring points within the plane threshold,
// cell by cell, nearest to the seed first, publishing a snapshot after every cell that added
// points, until no cell adds anything. Works at one level of detail: the level whose spacing
// matches the density d of the parameters.
//
// The final result also carries the edges and corners between the segments (section 4.1).
// Not yet here (next steps of the issue): the adaptive resolution of section 3.6 (switching
// levels when the observed spacing drifts from d), the alpha-shape outline of each segment, and
// edges and corners in the intermediate snapshots.

#include <Eigen/Core>
#include <atomic>
#include <cstdint>
#include <functional>
#include <vector>

#include "engine/lod/node_cache.h"
#include "reco/edges_and_corners.h"
#include "reco/parameters.h"
#include "reco/plane_regression.h"

namespace plumb::reco {

struct GrowOptions {
  std::size_t max_planes = 3;  // seed planes (section 3.4)
  bool drop_unstable = true;   // Otsu on the seed planes' support
  std::uint64_t random_seed = 1;
  // Cancels the grow between two cells when it becomes true (a newer click, say). May be null.
  const std::atomic<bool>* cancel = nullptr;
};

// One segment: a regression and what it has gathered.
struct SegmentSnapshot {
  Plane plane;               // synthesised from the regression (valid once it has 3 points)
  std::uint64_t points = 0;  // inliers added, seed points included
};

// An immutable picture of the grow at one moment; safe to hand to another thread.
struct GrowSnapshot {
  std::vector<SegmentSnapshot> segments;
  std::vector<Edge> edges;             // final result only: between segments, with their support range
  std::vector<Corner> corners;         // final result only
  std::uint32_t level = 0;             // octree level worked on
  std::uint64_t cells_visited = 0;     // cell visits (a cell is visited again when a neighbour grows to it)
  std::uint64_t points_tested = 0;     // candidate point-to-plane tests
  double mean_neighbour_distance = 0;  // d_avg: mean distance from an added point to the point that reached it
  double elapsed_ms = 0;
  bool converged = false;  // no cell adds anything any more
  bool cancelled = false;
};

using GrowProgress = std::function<void(const GrowSnapshot&)>;

// Grows planes around parameters.seed. Calls `progress` (if set) on this thread after each cell
// that added points; returns the final snapshot. Reads the octree through `cache` (thread-safe,
// shared with other users).
GrowSnapshot growRegions(lod::NodeCache& cache, const GrowParameters& parameters, const GrowOptions& options = {},
                         const GrowProgress& progress = {});

}  // namespace plumb::reco
