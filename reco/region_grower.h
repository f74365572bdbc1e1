#pragma once
// The interactive region growing loop (paper section 3.5) on an out-of-core octree: from the
// seed planes around a picked point, add the neighbouring points within the plane threshold,
// cell by cell, nearest to the seed first, publishing a snapshot after every cell that added
// points, until no cell adds anything. It starts at the level whose spacing matches the density d
// of the parameters and switches levels where the observed density drifts from d (section 3.6).
//
// The final result also carries the edges and corners between the segments (section 4.1).

#include <Eigen/Core>
#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include "engine/lod/lod_query.h"
#include "engine/lod/node_cache.h"
#include "reco/edges_and_corners.h"
#include "reco/outline.h"
#include "reco/parameters.h"
#include "reco/plane_regression.h"

namespace plumb::reco {

struct GrowOptions {
  std::size_t max_planes = 3;  // seed planes (section 3.4), at most 32
  bool drop_unstable = true;   // Otsu on the seed planes' support
  std::uint64_t random_seed = 1;
  // Adaptive resolution (section 3.6). The observed density is (spacing / s_obs)^2, an areal
  // density relative to the wanted one, where s_obs is a running mean of the distance from each
  // added point to its nearest segment point: a queued cell is replaced by its eight children
  // when it falls below refine_below (where the octree has finer points there), and cells move
  // to their parents (mark and finish) when it rises above coarsen_above, never coarser than the
  // level d asks for. The paper's thresholds: a level step divides a plane's points by four.
  bool adaptive_resolution = true;
  double refine_below = 0.5;
  double coarsen_above = 4.0;
  std::uint32_t max_refine_levels = 3;  // how much finer than the starting level a cell may go
  // The inlier test (section 3.5) with the scanner's noise in mind: a point joins within
  // min(t_p, noise_sigmas x the plane's RMS), never below min_threshold_fraction x t_p.
  // noise_sigmas = 0 gives the paper's plain t_p.
  double noise_sigmas = 2.25;
  double min_threshold_fraction = 0.1;
  // And only where the surface around the point continues the segment's: the mean offset of the
  // free points around it and that of the segment's points around it differ by at most
  // continuity x the threshold (a parallel surface just behind, a door leaf in its recess, stays
  // out). 0 turns the test off.
  double continuity = 0.5;
  // Where the growth stops, a segment that covers less than the seed disc (pi r_s^2) may take the
  // free points within r_s / 2 of it that lie on its plane and go on growing from them: the gaps
  // between a grazing floor's scan lines, a shadow (region_grower.cpp, bridgeGaps).
  bool bridge_gaps = true;
  // After convergence, move each point to the nearest plane among the segments around it and
  // refit (the growth gives a point to whichever segment reaches it first).
  bool settle = true;
  // Then refit each plane robustly (robust_plane_fit.h): Tukey's biweight over a window of
  // refine_c robust standard deviations of its residuals, refine_rounds times, over its points
  // and the unassigned ones around them; the last fit gives the points inside a segment, away
  // from its border, full weight (interior_points.h). 0 keeps the least-squares fit of the grown
  // points.
  double refine_c = 3.5;
  std::uint32_t refine_rounds = 4;
  // Where the grow works in finer cells than those the seed gathers its sphere in (full detail
  // on a dense scan), the seed deals the gathered points out to them; false gathers them again
  // (slower, the same grow: the tests compare the two).
  bool deal_seed_cells = true;
  // Fill SegmentSnapshot::members in the final result (the octree points of each segment).
  bool collect_members = false;
  // Only the points this keeps take part (a view's section: grows limited to what it shows);
  // empty: every point. Called once for each point a grow loads, from the grow's thread.
  std::function<bool(const Eigen::Vector3d&)> keep;
  // Cancels the grow between two cells when it becomes true (a newer click, say). May be null.
  const std::atomic<bool>* cancel = nullptr;
};

// One segment: a regression and what it has gathered.
struct SegmentSnapshot {
  Plane plane;               // synthesised from the regression (valid once it has 3 points)
  std::uint64_t points = 0;  // inliers added, seed points included
  // The regression polygon (section 3.6, progress callback): the outline of the segment's points
  // on its plane, alpha = r, with its triangulation; area = outline->shape.area_m2. Shared and
  // immutable. To keep snapshots cheap it is redrawn when the segment has grown by a quarter
  // since the last drawing (always in the final result), so in an intermediate snapshot it may
  // trail the point count a little. Null for a segment without a valid plane.
  std::shared_ptr<const PlaneOutline> outline;
  // The segment's points as octree identities, each once; final result only, and only when
  // GrowOptions::collect_members asks for them.
  std::vector<lod::PointRef> members;
};

// An immutable picture of the grow at one moment; safe to hand to another thread.
struct GrowSnapshot {
  std::vector<SegmentSnapshot> segments;
  // Between segments, with their support ranges (section 4.1). Recomputed when the segments
  // together have grown by a quarter (always in the final result).
  std::vector<Edge> edges;
  std::vector<Corner> corners;
  std::uint32_t level = 0;         // the starting octree level, whose spacing matches d
  std::uint32_t finest_level = 0;  // the finest and coarsest levels of the cells processed
  std::uint32_t coarsest_level = 0;
  std::uint64_t refinements = 0;       // cells replaced by their children (section 3.6)
  std::uint64_t coarsenings = 0;       // groups of cells replaced by their parent
  double data_spacing_m = 0;           // median nearest-neighbour distance of the seed points
  double search_radius_m = 0;          // r as used: the parameters', wider where the data is sparser
  double plane_threshold_m = 0;        // t_p as used: the parameters', or measured from the data
  double noise_sigma_m = 0;            // the seed planes' noise where t_p was measured, else 0
  double front_spacing_m = 0;          // s_obs: the running nearest-neighbour spacing of the growth front
  std::uint64_t cells_visited = 0;     // cell visits (a cell is visited again when a neighbour grows to it)
  std::uint64_t points_tested = 0;     // candidate point-to-plane tests
  std::uint64_t tests_skipped = 0;     // tests of a rejected point repeated before any plane changed
  std::uint64_t bridges = 0;           // gaps wider than r that a starved segment crossed (bridge_gaps)
  double mean_neighbour_distance = 0;  // d_avg: mean distance from an added point to the point that reached it
  double elapsed_ms = 0;
  // When the seed sphere at d's density was published with its planes (at full detail a sample's
  // snapshot comes first), from the grow's start; set once the seed is done.
  double seeded_ms = 0;
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
