#pragma once
// One grow's state, shared by the stages of the region grower (region_grower.h), each in a file
// of its own:
//   region_grower.cpp   the loop, the seed and the snapshots (its comment lists every step)
//   grow_cells.cpp      cells, claims and the frontier; the adaptive resolution (section 3.6)
//   grow_points.cpp     the growth point by point: the inlier test, refits (section 3.5)
//   grow_bridges.cpp    bridges over gaps wider than r where the growth stops
//   grow_final_fit.cpp  settling the points where segments meet, the robust final fit
// Internal to reco/: growRegions is the only user.

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <optional>
#include <queue>
#include <span>
#include <tuple>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include "engine/lod/lod_query.h"
#include "reco/cell_claims.h"
#include "reco/grid_index.h"
#include "reco/grid_map.h"
#include "reco/point_grid.h"
#include "reco/region_grower.h"
#include "reco/seed_planes.h"

namespace plumb::reco::detail {

using Clock = std::chrono::steady_clock;
using lod::CellKey;

// A point identity as one hashable number.
inline std::uint64_t refKey(const lod::PointRef& ref) {
  return (std::uint64_t{ref.node} << 32) | ref.index;
}

inline std::array<double, 3> array(const Eigen::Vector3d& p) {
  return {p.x(), p.y(), p.z()};
}

// Which segment each octree point joined: one byte per point of every node the grow touched
// (0 for none, s + 1 for segment s). A point has one identity at every level, so this is what
// keeps a point from being counted twice when the grow switches levels.
class Membership {
 public:
  explicit Membership(const lod::Octree& octree) : octree_(octree) {}
  Membership(const Membership&) = delete;
  Membership& operator=(const Membership&) = delete;
  // 0 for none, s + 1 for segment s.
  std::uint8_t flag(const lod::PointRef& ref) { return node(ref.node)[ref.index]; }
  void assign(const lod::PointRef& ref, std::uint32_t segment) {
    node(ref.node)[ref.index] = static_cast<std::uint8_t>(segment + 1);
  }
  void release(const lod::PointRef& ref) { node(ref.node)[ref.index] = 0; }
  std::vector<std::vector<lod::PointRef>> members(std::size_t segments) const {
    std::vector<std::vector<lod::PointRef>> result(segments);
    for (const auto& [node, flags] : nodes_) {
      for (std::uint32_t i = 0; i < flags.size(); ++i) {
        if (flags[i] != 0) result[flags[i] - 1u].push_back({node, i});
      }
    }
    for (auto& list : result) {
      std::sort(list.begin(), list.end(), [](const lod::PointRef& a, const lod::PointRef& b) {
        return std::tie(a.node, a.index) < std::tie(b.node, b.index);
      });
    }
    return result;
  }

 private:
  std::vector<std::uint8_t>& node(std::uint32_t index) {
    if (last_ != nullptr && last_index_ == index) return *last_;
    auto [it, inserted] = nodes_.try_emplace(index);
    if (inserted) it->second.assign(octree_.nodes()[index].point_count, 0);
    last_index_ = index;
    last_ = &it->second;
    return *last_;
  }
  const lod::Octree& octree_;
  std::unordered_map<std::uint32_t, std::vector<std::uint8_t>> nodes_;
  // The node asked for last: points come a node at a time (a cell's load, the seed's inliers).
  std::uint32_t last_index_ = 0;
  std::vector<std::uint8_t>* last_ = nullptr;
};

struct Assigned {
  Eigen::Vector3d position;
  std::uint32_t segment;
};

// The assigned points of one neighbour-grid cell, and which segments they belong to: a search
// for "a point of each segment within r" skips the cells with no segment it has not yet seen,
// which, where the points are dense, is nearly all of them.
struct AssignedCell {
  std::uint32_t segments = 0;  // bit s: a point of segment s is here
  std::vector<Assigned> points;
};

// CellState::rejected_epoch of a point no segment has tested yet.
inline constexpr std::uint32_t kNeverTested = ~std::uint32_t{0};

struct CellState {
  void reserve(std::size_t n) {
    points.reserve(n);
    refs.reserve(n);
    assigned.reserve(n);
    rejected_epoch.reserve(n);
    rejected_by.reserve(n);
  }
  // Records that point `index` joined the segment of `flag` (s + 1).
  void join(std::uint32_t index, std::uint8_t flag) {
    assigned[index] = flag;
    if (!grid_place.empty()) assigned_by_grid[grid_place[index]] = flag;
  }
  // Sets the cell's search radius and indexes its points by a grid of that step.
  void index(double search_radius, const Eigen::Vector3d& grid_origin) {
    radius = search_radius;
    grid = PointGrid(grid_origin, search_radius);
    by_grid = GridIndex(grid, points);
    const std::vector<std::uint32_t>& order = by_grid.order();
    assigned_by_grid.resize(order.size());
    grid_place.resize(order.size());
    for (std::uint32_t k = 0; k < order.size(); ++k) {
      assigned_by_grid[k] = assigned[order[k]];
      grid_place[order[k]] = k;
    }
  }
  // Appends a point that no segment has tested yet.
  void add(const Eigen::Vector3d& position, const lod::PointRef& ref, std::uint8_t segment_flag) {
    points.push_back(position);
    refs.push_back(ref);
    assigned.push_back(segment_flag);
    rejected_epoch.push_back(kNeverTested);
    rejected_by.push_back(0);
  }

  bool loaded = false;
  bool processed = false;
  std::vector<Eigen::Vector3d> points;
  std::vector<lod::PointRef> refs;
  // Which segment each point joined during the growth (0 for none, s + 1 for segment s):
  // Membership's flag, kept here because the growth asks it for every candidate and its
  // neighbours. Claims are disjoint, so while this cell exists its points join only through it.
  // (Settle and refine move points between segments afterwards in Membership only.)
  std::vector<std::uint8_t> assigned;
  // For a point that no segment took: the plane epoch of its last test, and the segments it was
  // tested against then (bit s). A test repeated from another border point of one of those
  // segments, before any plane has changed, would give the same answer, and is skipped: at full
  // detail each rejected point has a dozen neighbours that reach it.
  std::vector<std::uint32_t> rejected_epoch;
  std::vector<std::uint32_t> rejected_by;
  // The cell's own search radius and neighbour grid (indexCell): r, or less where the cell's
  // points are much denser than the seed's (at full detail, the surfaces nearer the scanner).
  double radius = 0.0;
  PointGrid grid{Eigen::Vector3d::Zero(), 1.0};
  GridIndex by_grid;  // the points by cell of `grid`
  // `assigned` in by_grid's order, and each point's place in that order: the continuity test
  // reads the owners of a grid cell's points one after another, as it reads their positions.
  std::vector<std::uint8_t> assigned_by_grid;
  std::vector<std::uint32_t> grid_place;
  // Where `radius` is less than r: the points by cell of a grid of r, made when a point of a
  // surface sparser than the cell's bulk is first searched within r (processCell).
  std::optional<GridIndex> by_wide_grid;
  std::vector<Assigned> frontier;  // assigned points within r of this cell, not yet expanded here
};

struct Candidate {
  int segment = -1;             // the segment the point joins, -1 for none
  double nearest_m = INFINITY;  // distance to the nearest assigned point (any segment)
  std::uint32_t tested = 0;     // bit s: segment s has a point within r, and its plane was tested
};

class Grower {
 public:
  Grower(lod::NodeCache& cache, const GrowParameters& parameters, const GrowOptions& options,
         const GrowProgress& progress);
  GrowSnapshot run();

 private:
  // region_grower.cpp: the loop, the seed, the snapshots
  struct SeedSphere {
    std::vector<CellKey> cells;                             // claimed
    std::vector<Eigen::Vector3d> points;                    // within r_s of the seed
    std::vector<std::pair<CellKey, std::uint32_t>> origin;  // each point's cell and index there
  };
  std::uint32_t cellLevelFor(double width, std::uint32_t finest) const;
  std::vector<CellKey> seedCells(std::uint32_t cell_level) const;
  void claimSeedCells(std::uint32_t cell_level, SeedSphere& sphere);
  void dealSeedCells(std::uint32_t cell_level, SeedSphere& sphere);
  double seedPlaneNoise(std::span<const Eigen::Vector3d> points, const std::vector<SeedPlane>& planes, double window,
                        std::size_t stride = 1) const;
  std::vector<SeedPlane> seedPlanesMeasuringThreshold(std::span<const Eigen::Vector3d> points, SeedOptions options);
  std::vector<SeedPlane> findPlanes(std::span<const Eigen::Vector3d> points, const SeedOptions& options);
  std::uint32_t seedSampleLevel(std::uint32_t finest) const;
  std::vector<SeedPlane> seedFromSample(std::uint32_t sample_level, std::uint32_t cell_level,
                                        const SeedOptions& options);
  std::vector<SeedPlane> pointsOnPlanes(std::span<const Eigen::Vector3d> points, const std::vector<SeedPlane>& planes,
                                        double threshold);
  void forgetCells();
  double reachFor(double spacing) const;
  void adaptToDataSpacing(const std::vector<Eigen::Vector3d>& seed_points, const std::vector<SeedPlane>& planes);
  void seed();
  void fillSnapshot(bool final);
  void publish();
  GrowSnapshot finish(bool converged);

  // grow_cells.cpp: cells, claims and the frontier; adaptive resolution (section 3.6)
  CellState& loaded(const CellKey& key);
  void indexCell(CellState& state) const;
  void enqueue(const CellKey& key);
  void spreadFrontier(const Eigen::Vector3d& p, std::uint32_t segment, const CellKey& holder, CellState& holder_state);
  std::optional<double> densityRatio() const;
  bool adapt(const CellKey& key);
  void replaceByChildren(const CellKey& key);
  void lockLevel(std::uint32_t level);
  void unlockLevel();
  bool canMerge(const CellKey& parent);

  // grow_points.cpp: the growth, point by point (section 3.5)
  void addToGrid(const Eigen::Vector3d& p, std::uint32_t segment);
  void assign(const CellKey& key, CellState& state, std::uint32_t index, std::uint32_t segment);
  struct KnownNeighbour {
    std::uint32_t segment;
    double distance2;
  };
  Candidate bestSegment(const Eigen::Vector3d& p, bool measure,
                        const std::optional<KnownNeighbour>& known = std::nullopt);
  void observeSpacing(double nearest_m);
  bool processCell(const CellKey& key);
  bool continuesSurface(const CellState& state, const Eigen::Vector3d& p, std::uint32_t segment,
                        std::vector<std::uint32_t>* free_around, std::uint32_t* around) const;
  void refit(std::uint32_t segment);
  void updateThreshold(std::uint32_t segment);

  // grow_bridges.cpp: bridges over gaps wider than r
  bool bridgeGaps();
  using PointsByGridCell = std::unordered_map<GridKey, std::vector<Eigen::Vector3d>, GridKeyHash>;
  bool bridge(std::uint32_t s, double reach);
  std::vector<CellKey> cellsWithinReach(const PointsByGridCell& own, const PointGrid& coarse, double reach);

  // grow_final_fit.cpp: settling and the robust final fit
  void settle();
  void rebuildAssigned();
  std::uint32_t segmentsNear(const Eigen::Vector3d& p, std::uint32_t known) const;
  std::uint32_t segmentsAround(const Eigen::Vector3d& p) const;
  void refine();

  static constexpr std::uint64_t kMinFrontSamples = 16;
  // The seed finds its planes on a sample of the sphere no finer than r_s / this (seed): several
  // hundred to a few thousand points on the surfaces through it, enough for RANSAC and the noise
  // (medium detail grows at about r_s / 11), found and published within milliseconds whatever
  // the cloud's depth. At r_s / 32 the sample's octree nodes took 5 to 13 ms to read on the 1 M
  // and 10 M rooms; at r_s / 16 (the root node there) 4 to 7 ms, with the same corners.
  static constexpr double kSeedSampleSpacings = 16.0;
  // reachFor: r^3 = kSlabReach sigma s^2 gives a point in a noisy slab 4 pi neighbours within r.
  static constexpr double kSlabReach = 4.0 * M_PI / 1.18;
  // Cells at least this many r wide (seed): at the octree's own spacing they are 64 r wide.
  static constexpr double kMinCellRadii = 8.0;
  // The seed deals its gathered cells' points out to cells at most this many levels finer
  // (dealSeedCells: a table of 8^levels per gathered cell); further, it gathers again.
  static constexpr std::uint32_t kMaxDealLevels = 6;
  // A cell's own search radius is at least r / kMaxRadiusShrink (indexCell).
  static constexpr double kMaxRadiusShrink = 8.0;
  // A point with fewer neighbours than this within its cell's shrunk radius (its surface's own
  // or free) lies on a surface sparser than the cell's bulk: it is searched within r as well.
  // Within the shrunk radius, about two of its spacings, the bulk's points have a dozen.
  static constexpr std::uint32_t kMinShrunkNeighbours = 3;
  // The seed planes' noise is measured on at least this many inliers, else on patches alone.
  static constexpr std::size_t kMinNoiseResiduals = 30;
  // The noise for the reach where t_p is given is measured on about this many inliers.
  static constexpr std::size_t kReachNoiseResiduals = 20000;
  static constexpr std::size_t kMaxSegments = 32;  // segment masks are 32 bits wide
  // segmentsAround: a point on a segment's border has the segment's points to one side, their
  // mean 4 / (3 pi) = 0.42 r from it (a half disc); inside, a dozen points' mean strays about
  // 0.18 r. 0.3 r keeps nine in ten inside and a fifth of those on the border.
  static constexpr double kInsideOffset = 0.3;
  static constexpr std::uint32_t kMinAroundPoints = 4;
  // refine's last fit leaves out the points near a segment's border that lie to one side of its
  // plane (oneSidedBorderPoints): within kBorderBandSigmas robust sigmas of the border (and a
  // cell), where the mean offset of a cell and its neighbours is over kOneSidedZ standard errors
  // and kOneSidedSigmas sigmas.
  static constexpr double kBorderBandSigmas = 6.0;
  static constexpr double kOneSidedZ = 3.0;
  static constexpr double kOneSidedSigmas = 0.25;
  static constexpr std::uint32_t kMinContinuityPoints = 4;
  // A floor seen at grazing angles needs a bridge per scan line until it reaches denser ground;
  // this bounds the work where a segment keeps finding a point or two beyond r.
  static constexpr std::uint32_t kMaxBridges = 32;

  const lod::Octree& octree_;
  lod::CellPointIndex cell_points_;
  GrowParameters parameters_;
  GrowOptions options_;
  const GrowProgress& progress_;
  double radius_;                  // r: the parameters', or wider where the data is sparser (adaptToDataSpacing)
  bool radius_from_data_ = false;  // r follows the seed's data spacing, not d's
  // The seed planes' noise, for the reach (reachFor): the snapshot's where t_p was measured,
  // measured all the same where the user gave t_p.
  double reach_sigma_ = 0.0;
  PointGrid grid_;
  CellClaims claims_;
  Membership membership_;
  Clock::time_point start_;
  std::uint32_t base_level_ = 0;
  std::uint32_t working_level_ = 0;  // the level new cells are claimed at
  // How many levels finer than its cell's level a cell's points go (seed): 0 but where r is many
  // times the spacing of the level d asks for (full detail).
  std::uint32_t point_levels_ = 0;
  bool gathering_seed_ = false;  // cells load unindexed: r is not known yet (seed)

  GrowSnapshot snapshot_;
  std::vector<PlaneRegression> regressions_;
  std::vector<Plane> planes_;                                 // the regressions' planes, refitted as they grow
  std::vector<std::uint64_t> fitted_count_;                   // regression size at the last refit
  std::vector<double> thresholds_;                            // per segment: what a point may be off its plane
  std::vector<std::uint32_t> bridges_left_;                   // per segment: bridges it may still try
  std::vector<std::vector<Eigen::Vector3d>> segment_points_;  // for outlines, edges and corners
  std::vector<std::vector<lod::PointRef>> segment_refs_;      // the same points' identities
  std::vector<bool> grown_;
  std::vector<std::uint64_t> outlined_count_;  // segment size when its outline was last drawn
  std::uint64_t featured_total_ = 0;           // all segments' size when the features were last found
  std::unordered_map<CellKey, CellState, lod::CellKeyHash> cells_;
  // The segments' points by cell of grid_, whose step is 2 r (segmentGrid): the 8 cells nearest
  // a point hold all within r of it (PointGrid::forEachNear), 8 lookups a search where a grid of
  // r took 27.
  // Unlike a cell's own grid (CellState::grid), a search here mostly stops at the first point
  // of each segment within r, so the wider cells' extra points cost little.
  GridMap<AssignedCell> assigned_;
  std::priority_queue<std::pair<double, CellKey>, std::vector<std::pair<double, CellKey>>, std::greater<>> queue_;
  std::unordered_set<CellKey, lod::CellKeyHash> queued_;
  std::optional<CellKey> processing_;  // the cell whose breadth-first search is running
  std::uint32_t plane_epoch_ = 0;      // counts the refits: a rejected point's test holds until the next
  double neighbour_distance_sum_ = 0.0;
  std::uint64_t neighbour_distance_count_ = 0;
  double front_spacing_ = 0.0;
  std::uint64_t front_samples_ = 0;

  // Mark and finish (section 3.6): while a level is locked, its cells outside the marked
  // parents wait.
  std::optional<std::uint32_t> locked_level_;
  std::unordered_set<CellKey, lod::CellKeyHash> marked_parents_;
  std::vector<CellKey> waiting_;
};

}  // namespace plumb::reco::detail
