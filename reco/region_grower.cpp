// Seeded incremental region growing, paper section 3.5 (the seed of 3.4 and the adaptive
// resolution of 3.6 included).
//
//   1. Level: the octree level whose spacing matches the wanted density d.
//   2. Seed: the points of that level within r_s of the picked point; up to three planes by
//      RANSAC (seed_planes.h); each starts a regression with its inliers.
//   3. Loop over a queue of cells, nearest to the seed first. A cell of level L holds the points
//      of levels 0..L in it (lod::pointsInCell). Its frontier is the assigned points within r
//      of it; breadth-first from the frontier, an unassigned point within r of an assigned one
//      joins the segment with the nearest plane among those within t_p whose points are within r
//      of it (a point joins at most one segment), where the surface around it continues the
//      segment's (continuesSurface). New points extend the frontier, also into the
//      neighbouring cells they are within r of, which are claimed and queued (again).
//   4. Adaptive resolution, as a cell leaves the queue: where the observed density is below
//      refine_below x d and the octree has finer points, the cell is replaced by its children.
//      Where it is above coarsen_above x d, the level is locked: the cells inside the parents of
//      the cells claimed so far are finished at that level (mark), the others wait; then those
//      that wait move to their parents if the density is still too high (finish). Points are
//      octree identities (lod::PointRef), so a point met again at another level is known.
//   5. After a cell that added points, refit the grown planes and publish a snapshot: planes,
//      outlines (outline.h) and the edges and corners between the segments (edges_and_corners.h),
//      the last two redrawn as the segments grow by a quarter.
//   6. When the queue is empty, each segment may bridge a gap wider than r (bridgeGaps): the free
//      points on its plane within r_s / 2 of it join, and the loop goes on from them. Stop when
//      no bridge finds anything (converged) or the cancel flag is set (checked per cell).
//   7. Settle (converged grows): points near where segments meet move to the nearest plane
//      among the segments around them, and the planes are refitted.
//   8. Refine (converged grows): each plane's final fit is a robust M-estimate over the points
//      around its segment (robust_plane_fit.h), which may take in points the growth turned away
//      and give up others, and then a least-squares fit where the points lie away from the
//      segment's border (interior_points.h); the final result has everything drawn anew.

#include "reco/region_grower.h"

#include <algorithm>
#include <cassert>
#include <chrono>
#include <cmath>
#include <map>
#include <optional>
#include <queue>
#include <unordered_map>
#include <unordered_set>

#include "reco/cell_claims.h"
#include "reco/interior_points.h"
#include "reco/point_grid.h"
#include "reco/point_spacing.h"
#include "reco/robust_plane_fit.h"
#include "reco/seed_planes.h"

namespace plumb::reco {
namespace {

using Clock = std::chrono::steady_clock;
using lod::CellKey;

std::array<double, 3> array(const Eigen::Vector3d& p) {
  return {p.x(), p.y(), p.z()};
}

// Which segment each octree point joined: one byte per point of every node the grow touched
// (0 for none, s + 1 for segment s). A point has one identity at every level, so this is what
// keeps a point from being counted twice when the grow switches levels.
class Membership {
 public:
  explicit Membership(const lod::Octree& octree) : octree_(octree) {}
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
    auto [it, inserted] = nodes_.try_emplace(index);
    if (inserted) it->second.assign(octree_.nodes()[index].point_count, 0);
    return it->second;
  }
  const lod::Octree& octree_;
  std::unordered_map<std::uint32_t, std::vector<std::uint8_t>> nodes_;
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

struct CellState {
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
  std::unordered_map<GridKey, std::vector<std::uint32_t>, GridKeyHash> by_grid;
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
         const GrowProgress& progress)
      : cache_(cache),
        octree_(cache.octree()),
        parameters_(parameters),
        options_(options),
        progress_(progress),
        radius_(parameters.search_radius_m),
        grid_(parameters.seed, parameters.search_radius_m),
        claims_(octree_.cube()),
        membership_(octree_),
        start_(Clock::now()) {
    base_level_ = octree_.levelForSpacing(parameters.spacing_m);
    snapshot_.level = base_level_;
    snapshot_.finest_level = snapshot_.coarsest_level = base_level_;
    working_level_ = base_level_;
  }

  GrowSnapshot run() {
    seed();
    for (;;) {
      if (queue_.empty()) {
        if (locked_level_) {
          unlockLevel();
          continue;
        }
        if (bridgeGaps()) continue;
        break;
      }
      if (options_.cancel != nullptr && options_.cancel->load()) {
        snapshot_.cancelled = true;
        return finish(false);
      }
      const CellKey key = queue_.top().second;
      queue_.pop();
      queued_.erase(key);
      if (!claims_.claimed(key)) continue;  // replaced by its children or parent since it was queued
      if (adapt(key)) continue;
      if (processCell(key)) publish();
    }
    return finish(true);
  }

 private:
  // --- cells and claims ---------------------------------------------------------------------

  CellState& loaded(const CellKey& key) {
    CellState& state = cells_[key];
    if (!state.loaded) {
      state.loaded = true;
      const std::vector<lod::CellPoint> points = lod::pointsInCell(cache_, key);
      for (const lod::CellPoint& p : points) {
        const Eigen::Vector3d position(p.position[0], p.position[1], p.position[2]);
        state.by_grid[grid_.keyOf(position)].push_back(static_cast<std::uint32_t>(state.points.size()));
        state.points.push_back(position);
        state.refs.push_back(p.ref);
        state.assigned.push_back(membership_.flag(p.ref));
        state.rejected_epoch.push_back(kNeverTested);
        state.rejected_by.push_back(0);
      }
    }
    return state;
  }

  void enqueue(const CellKey& key) {
    if (!queued_.insert(key).second) return;
    queue_.push({octree_.cube().squaredDistance(key, array(parameters_.seed)), key});
  }

  // Hands p to the frontier of every claimed cell within r of it other than the one being
  // processed (whose breadth-first search has p already), claiming cells where none is yet.
  void spreadFrontier(const Eigen::Vector3d& p, std::uint32_t segment) {
    // Cells are at least 64 search radii wide: only the sides of the processed cell's box that p
    // is within r of lead to a neighbour (during the seed, with no cell processed, all do).
    std::array<std::array<int, 3>, 3> steps{};  // per axis: the offsets to try, -1, 0 or +1
    std::array<std::size_t, 3> step_count{};
    for (std::size_t a = 0; a < 3; ++a) {
      steps[a][step_count[a]++] = 0;
      if (!processing_box_ || p[static_cast<Eigen::Index>(a)] - radius_ <= processing_box_->min[a]) {
        steps[a][step_count[a]++] = -1;
      }
      if (!processing_box_ || p[static_cast<Eigen::Index>(a)] + radius_ >= processing_box_->max[a]) {
        steps[a][step_count[a]++] = 1;
      }
    }
    if (step_count[0] * step_count[1] * step_count[2] == 1) return;
    std::array<CellKey, 27> seen;
    std::size_t count = 0;
    for (std::size_t iz = 0; iz < step_count[2]; ++iz) {
      for (std::size_t iy = 0; iy < step_count[1]; ++iy) {
        for (std::size_t ix = 0; ix < step_count[0]; ++ix) {
          const Eigen::Vector3d q = p + radius_ * Eigen::Vector3d(steps[0][ix], steps[1][iy], steps[2][iz]);
          bool created = false;
          const CellKey key = claims_.claimAt(array(q), working_level_, octree_.header().depth, created);
          const auto end = seen.begin() + static_cast<std::ptrdiff_t>(count);
          if (std::find(seen.begin(), end, key) != end) continue;
          seen[count++] = key;
          if (processing_ && key == *processing_) continue;
          cells_[key].frontier.push_back({p, segment});
          enqueue(key);
        }
      }
    }
  }

  // --- adaptive resolution (section 3.6) -----------------------------------------------------

  // The observed areal density relative to the wanted one; nullopt until enough points tell.
  std::optional<double> densityRatio() const {
    if (front_samples_ < kMinFrontSamples || front_spacing_ <= 0.0) return std::nullopt;
    const double ratio = parameters_.spacing_m / front_spacing_;
    return ratio * ratio;
  }

  // Applies the adaptive resolution to `key` as it leaves the queue. Returns true when the cell
  // is not to be processed now (replaced, or waiting for a level change).
  bool adapt(const CellKey& key) {
    if (locked_level_) {
      // Finishing: only the marked cells of the locked level go on; the others wait.
      if (key.level == *locked_level_ && !marked_parents_.contains(*key.parent())) {
        waiting_.push_back(key);
        return true;
      }
      return false;
    }
    const auto ratio = densityRatio();
    if (!options_.adaptive_resolution || !ratio) return false;
    if (*ratio < options_.refine_below && !cells_[key].processed && key.level < octree_.header().depth &&
        key.level < base_level_ + options_.max_refine_levels) {
      const lod::NodeInfo* node = octree_.find(key);
      if (node != nullptr && node->child_mask != 0) {  // elsewhere the finer levels add no point
        replaceByChildren(key);
        return true;
      }
    }
    if (*ratio > options_.coarsen_above && key.level > base_level_) {
      lockLevel(key.level);
      return adapt(key);
    }
    return false;
  }

  void replaceByChildren(const CellKey& key) {
    std::vector<Assigned> frontier = std::move(cells_[key].frontier);
    cells_.erase(key);
    claims_.release(key);
    for (const CellKey& child : key.children()) {
      claims_.claim(child);
      CellState& state = cells_[child];
      for (const Assigned& a : frontier) {
        if (octree_.cube().squaredDistance(child, array(a.position)) <= radius_ * radius_) state.frontier.push_back(a);
      }
      if (!state.frontier.empty()) enqueue(child);
    }
    ++snapshot_.refinements;
    working_level_ = std::max(working_level_, key.level + 1);
    front_samples_ = 0;  // the next switch waits for what the new level shows
  }

  // Mark: the cells of `level` inside the parents of the cells claimed at that level so far
  // (processed, queued or idle siblings) are finished at this level before any of it moves up.
  void lockLevel(std::uint32_t level) {
    locked_level_ = level;
    marked_parents_.clear();
    for (const CellKey& key : claims_.cells()) {
      if (key.level == level) marked_parents_.insert(*key.parent());
    }
  }

  // Finish: the marked cells are done; each group of waiting cells moves to its parent if the
  // density is still too high there and nothing inside that parent was processed.
  void unlockLevel() {
    const std::uint32_t level = *locked_level_;
    locked_level_.reset();
    const auto ratio = densityRatio();
    const bool coarsen = ratio && *ratio > options_.coarsen_above;
    std::map<CellKey, std::vector<CellKey>> by_parent;
    for (const CellKey& key : waiting_) {
      if (claims_.claimed(key)) by_parent[*key.parent()].push_back(key);
    }
    waiting_.clear();
    for (const auto& [parent, children] : by_parent) {
      if (coarsen && canMerge(parent)) {
        std::vector<Assigned> frontier;
        for (const CellKey& child : parent.children()) {
          if (!claims_.claimed(child)) continue;
          auto& moved = cells_[child].frontier;
          frontier.insert(frontier.end(), moved.begin(), moved.end());
          cells_.erase(child);
          claims_.release(child);
        }
        claims_.claim(parent);
        cells_[parent].frontier = std::move(frontier);
        enqueue(parent);
        ++snapshot_.coarsenings;
        front_samples_ = 0;
      } else {
        for (const CellKey& child : children) enqueue(child);
      }
    }
    working_level_ = coarsen ? level - 1 : level;
  }

  // Whether the children of `parent` can give way to it: none processed, none with claims below.
  bool canMerge(const CellKey& parent) {
    for (const CellKey& child : parent.children()) {
      if (claims_.claimedBelow(child)) return false;
      if (claims_.claimed(child) && cells_[child].processed) return false;
    }
    return true;
  }

  // --- growing (section 3.5) ------------------------------------------------------------------

  // Enters a segment's point in the neighbour grid.
  void addToGrid(const Eigen::Vector3d& p, std::uint32_t segment) {
    AssignedCell& cell = assigned_[grid_.keyOf(p)];
    cell.segments |= 1u << segment;
    cell.points.push_back({p, segment});
  }

  // Records point i of a cell as joining `segment`.
  void assign(CellState& state, std::uint32_t index, std::uint32_t segment) {
    membership_.assign(state.refs[index], segment);
    state.assigned[index] = static_cast<std::uint8_t>(segment + 1);
    const Eigen::Vector3d& p = state.points[index];
    regressions_[segment].add(p);
    segment_points_[segment].push_back(p);
    segment_refs_[segment].push_back(state.refs[index]);
    addToGrid(p, segment);
    grown_[segment] = true;
    // The plane follows the regression as it grows (the paper tests each point against the
    // current regression): refit whenever the support has grown by a tenth, so a seed plane
    // from a few points straightens out long before its error matters, at O(log n) refits.
    if (regressions_[segment].count() >= fitted_count_[segment] + fitted_count_[segment] / 10 + 8) refit(segment);
    spreadFrontier(p, segment);
  }

  // Section 3.7: r is twice the mean point spacing. The spacing d asks for is what the octree
  // gives where the scan is dense enough; where it is sparser (a distant wall, or --detail full,
  // which asks for the deepest level's spacing), the points are farther apart than d implies and
  // a search radius of twice d's spacing finds no neighbours. The seed points tell the spacing the
  // data has: the median nearest-neighbour distance, and each seed plane's areal spacing, which
  // also sees the gaps between scan lines (point_spacing.h). r follows the largest, at most half
  // of r_s. The density the grow aims for stays d: where the octree has finer points further on,
  // the adaptive resolution goes and gets them. Returns whether r changed.
  bool adaptToDataSpacing(const std::vector<Eigen::Vector3d>& seed_points, const std::vector<SeedPlane>& planes) {
    double data_spacing = medianNearestDistance(seed_points, 0.5 * parameters_.seed_radius_m);
    std::vector<Eigen::Vector3d> inliers;
    for (const SeedPlane& plane : planes) {
      inliers.clear();
      for (std::uint32_t i : plane.inliers) inliers.push_back(seed_points[i]);
      data_spacing = std::max(data_spacing, arealSpacing(plane.plane, inliers));
    }
    snapshot_.data_spacing_m = data_spacing;
    const bool widen = 2.0 * data_spacing > radius_;
    if (widen) {
      radius_ = std::min(2.0 * data_spacing, 0.5 * parameters_.seed_radius_m);
      grid_ = PointGrid(parameters_.seed, radius_);
    }
    snapshot_.search_radius_m = radius_;
    return widen;
  }

  void seed() {
    const double rs = parameters_.seed_radius_m;
    const auto seed_array = array(parameters_.seed);
    std::vector<Eigen::Vector3d> points;
    std::vector<std::pair<CellKey, std::uint32_t>> origin;
    std::vector<CellKey> seed_cells;
    // Every cell of the box around the sphere, also those without a node of their own: where a
    // branch ends in a leaf above the level, the cell's points come from its ancestors.
    const CellKey low =
        octree_.cube().cellAt({seed_array[0] - rs, seed_array[1] - rs, seed_array[2] - rs}, base_level_);
    const CellKey high =
        octree_.cube().cellAt({seed_array[0] + rs, seed_array[1] + rs, seed_array[2] + rs}, base_level_);
    for (std::uint32_t z = low.z; z <= high.z; ++z) {
      for (std::uint32_t y = low.y; y <= high.y; ++y) {
        for (std::uint32_t x = low.x; x <= high.x; ++x) {
          const CellKey key{base_level_, x, y, z};
          if (octree_.cube().squaredDistance(key, seed_array) > rs * rs) continue;
          seed_cells.push_back(key);
          claims_.claim(key);
          // Loaded before r is known: the neighbour grid of the cell is built anew below if r widens.
          const CellState& state = loaded(key);
          for (std::uint32_t i = 0; i < state.points.size(); ++i) {
            if ((state.points[i] - parameters_.seed).squaredNorm() <= rs * rs) {
              points.push_back(state.points[i]);
              origin.emplace_back(key, i);
            }
          }
        }
      }
    }
    SeedOptions seed_options;
    seed_options.threshold = parameters_.plane_threshold_m;
    seed_options.max_planes = std::min(options_.max_planes, kMaxSegments);
    seed_options.drop_unstable = options_.drop_unstable;
    seed_options.seed = options_.random_seed;
    const std::vector<SeedPlane> planes = findSeedPlanes(points, seed_options);
    if (adaptToDataSpacing(points, planes)) {
      for (const CellKey& key : seed_cells) {
        CellState& state = cells_[key];
        state.by_grid.clear();
        for (std::uint32_t i = 0; i < state.points.size(); ++i)
          state.by_grid[grid_.keyOf(state.points[i])].push_back(i);
      }
    }
    regressions_.resize(planes.size());
    planes_.resize(planes.size());
    fitted_count_.assign(planes.size(), 0);
    bridges_left_.assign(planes.size(), kMaxBridges);
    thresholds_.assign(planes.size(), parameters_.plane_threshold_m);
    segment_points_.resize(planes.size());
    segment_refs_.resize(planes.size());
    grown_.assign(planes.size(), false);
    for (std::uint32_t s = 0; s < planes.size(); ++s) {
      planes_[s] = planes[s].plane;  // the RANSAC refit, until the regression takes over
      updateThreshold(s);
      for (std::uint32_t i : planes[s].inliers) {
        CellState& state = cells_[origin[i].first];
        if (!state.assigned[origin[i].second]) assign(state, origin[i].second, s);
      }
      refit(s);
    }
    snapshot_.points_tested += points.size();
    if (!planes.empty()) publish();
  }

  // The segment an unassigned point p joins: the nearest plane within its threshold among the segments
  // with an assigned point within r of p; and how far the nearest assigned point is.
  // `measure`: also find the nearest assigned point (what the adaptive resolution observes), at
  // the cost of a distance to every assigned point of the cells around that may hold a nearer
  // one (p's own cell first); otherwise each segment's first point within r ends its search.
  Candidate bestSegment(const Eigen::Vector3d& p, bool measure) {
    Candidate best;
    double best_distance = INFINITY;
    double nearest2 = INFINITY;
    std::uint32_t seen_mask = 0;
    grid_.forEachAround(p, [&](const GridKey& key) {
      const auto it = assigned_.find(key);
      if (it == assigned_.end()) return;
      const bool unseen = (it->second.segments & ~seen_mask) != 0;
      if (!unseen && (!measure || grid_.squaredDistanceToCell(p, key) >= nearest2)) return;
      for (const Assigned& a : it->second.points) {
        if (!measure && ((seen_mask >> a.segment) & 1u)) continue;
        const double d2 = (a.position - p).squaredNorm();
        if (d2 > radius_ * radius_) continue;
        nearest2 = std::min(nearest2, d2);
        if ((seen_mask >> a.segment) & 1u) continue;
        seen_mask |= 1u << a.segment;
        ++snapshot_.points_tested;
        const Plane& plane = planes_[a.segment];
        if (!plane.valid) continue;
        best.tested |= 1u << a.segment;
        const double d = plane.distance(p);
        if (d < thresholds_[a.segment] && d < best_distance) {
          best_distance = d;
          best.segment = static_cast<int>(a.segment);
        }
      }
    });
    best.nearest_m = std::sqrt(nearest2);
    return best;
  }

  void observeSpacing(double nearest_m) {
    // A running mean over the last few dozen measured points: the density where the front is now.
    constexpr double kWeight = 1.0 / 32.0;
    front_spacing_ = front_samples_ == 0 ? nearest_m : front_spacing_ + kWeight * (nearest_m - front_spacing_);
    ++front_samples_;
  }

  // Breadth-first from the cell's frontier; returns whether any point was added.
  bool processCell(const CellKey& key) {
    ++snapshot_.cells_visited;
    snapshot_.finest_level = std::max(snapshot_.finest_level, key.level);
    snapshot_.coarsest_level = std::min(snapshot_.coarsest_level, key.level);
    processing_ = key;
    processing_box_ = octree_.cube().cellBox(key);
    working_level_ = key.level;  // new neighbours start at this cell's level
    CellState& state = loaded(key);
    state.processed = true;
    std::vector<Assigned> queue = std::move(state.frontier);
    state.frontier.clear();
    bool added = false;
    for (std::size_t next = 0; next < queue.size(); ++next) {
      const Assigned from = queue[next];
      grid_.forEachAround(from.position, [&](const GridKey& grid_key) {
        const auto it = state.by_grid.find(grid_key);
        if (it == state.by_grid.end()) return;
        for (std::uint32_t i : it->second) {
          if (state.assigned[i]) continue;
          const double distance = (state.points[i] - from.position).norm();
          if (distance > radius_) continue;
          if (state.rejected_epoch[i] == plane_epoch_ && ((state.rejected_by[i] >> from.segment) & 1u)) {
            ++snapshot_.tests_skipped;
            continue;
          }
          // One added point in four is measured: enough for a running mean of the spacing.
          const bool measure = (neighbour_distance_count_ & 3u) == 0;
          Candidate candidate = bestSegment(state.points[i], measure);
          if (candidate.segment >= 0 &&
              !continuesSurface(state, state.points[i], static_cast<std::uint32_t>(candidate.segment))) {
            candidate.segment = -1;
          }
          if (candidate.segment < 0) {
            state.rejected_epoch[i] = plane_epoch_;
            state.rejected_by[i] = candidate.tested;
            continue;
          }
          assign(state, i, static_cast<std::uint32_t>(candidate.segment));
          queue.push_back({state.points[i], static_cast<std::uint32_t>(candidate.segment)});
          neighbour_distance_sum_ += distance;
          ++neighbour_distance_count_;
          if (measure) observeSpacing(candidate.nearest_m);
          added = true;
        }
      });
    }
    processing_.reset();
    processing_box_.reset();
    if (added) {
      for (std::uint32_t s = 0; s < regressions_.size(); ++s) {
        if (grown_[s]) refit(s);
        grown_[s] = false;
      }
    }
    return added;
  }

  // --- bridging gaps -----------------------------------------------------------------------------

  // Where the growth has stopped, a segment may be stuck at a gap wider than r that the seed's
  // scale does not see: the scan lines of a floor seen at grazing angles, farther apart than the
  // points of the walls beside it (whose spacing sets r), or the shadow of a cabinet leg. Each
  // segment takes the free points within half the seed radius of its points that lie within its
  // threshold and that no segment within r of them accepts (the continuity test's rejects stay
  // out); the growth goes on from them at r. Returns whether any segment took a point.
  bool bridgeGaps() {
    if (!options_.bridge_gaps) return false;
    const double reach = 0.5 * parameters_.seed_radius_m;
    if (reach <= radius_) return false;  // r spans such gaps already
    bool bridged = false;
    for (std::uint32_t s = 0; s < regressions_.size(); ++s) {
      if (bridges_left_[s] == 0 || !planes_[s].valid) continue;
      if (bridge(s, reach)) {
        --bridges_left_[s];
        ++snapshot_.bridges;
        bridged = true;
      } else {
        bridges_left_[s] = 0;  // nothing within reach; the others' bridges do not change that
      }
    }
    return bridged;
  }

  using PointsByGridCell = std::unordered_map<GridKey, std::vector<Eigen::Vector3d>, GridKeyHash>;

  // One bridge from segment s: the free points within `reach` of its points that join it.
  bool bridge(std::uint32_t s, double reach) {
    const PointGrid coarse(parameters_.seed, reach);
    PointsByGridCell own;
    for (const Eigen::Vector3d& p : segment_points_[s]) own[coarse.keyOf(p)].push_back(p);
    const auto withinReach = [&](const Eigen::Vector3d& q) {
      bool found = false;
      coarse.forEachAround(q, [&](const GridKey& key) {
        const auto it = own.find(key);
        if (found || it == own.end()) return;
        found = std::any_of(it->second.begin(), it->second.end(),
                            [&](const Eigen::Vector3d& p) { return (p - q).squaredNorm() <= reach * reach; });
      });
      return found;
    };
    std::vector<std::pair<CellKey, std::uint32_t>> taken;
    for (const CellKey& key : cellsWithinReach(own, coarse, reach)) {
      CellState& state = loaded(key);
      for (std::uint32_t i = 0; i < state.points.size(); ++i) {
        const Eigen::Vector3d& q = state.points[i];
        if (state.assigned[i] || planes_[s].distance(q) >= thresholds_[s] || !withinReach(q)) continue;
        // A point that a segment within r accepts is the growth's to give (it turned it away,
        // or has yet to reach it).
        if (bestSegment(q, false).segment >= 0) continue;
        taken.emplace_back(key, i);
      }
    }
    for (const auto& [key, i] : taken) assign(cells_[key], i, s);
    if (!taken.empty()) refit(s);
    return !taken.empty();
  }

  // The cells that may hold points within `reach` of the points in the `coarse` grid cells
  // `own` (a grid of step `reach`): those the grid cells' boxes, widened by reach, meet, claimed
  // at the working level where none is claimed yet. Sorted, so that the points join in the same
  // order whatever the hashing.
  std::vector<CellKey> cellsWithinReach(const PointsByGridCell& own, const PointGrid& coarse, double reach) {
    const double step = std::min(octree_.cube().cellSize(working_level_), reach);
    std::unordered_set<CellKey, lod::CellKeyHash> result;
    for (const auto& entry : own) {
      const Eigen::Vector3d low = coarse.cellMin(entry.first) - Eigen::Vector3d::Constant(reach);
      const Eigen::Vector3d high = low + Eigen::Vector3d::Constant(3.0 * reach);
      std::array<double, 3> p{};
      for (p[2] = low.z();; p[2] = std::min(p[2] + step, high.z())) {
        for (p[1] = low.y();; p[1] = std::min(p[1] + step, high.y())) {
          for (p[0] = low.x();; p[0] = std::min(p[0] + step, high.x())) {
            bool created = false;
            result.insert(claims_.claimAt(p, working_level_, octree_.header().depth, created));
            if (p[0] >= high.x()) break;
          }
          if (p[1] >= high.y()) break;
        }
        if (p[2] >= high.z()) break;
      }
    }
    std::vector<CellKey> sorted(result.begin(), result.end());
    std::sort(sorted.begin(), sorted.end());
    return sorted;
  }

  // Whether the surface around p continues the segment's surface there: the mean offset from the
  // plane of the free points within r of p (p included) against that of the segment's own points
  // within r, both within twice the threshold, must differ by at most continuity x the threshold.
  // A plane test alone lets in the points of a parallel surface a few sigmas behind (a door leaf
  // in its recess, at high noise) one in twenty, each pulling the plane towards the rest of it;
  // the mean of a dozen neighbours is four times surer than one point. Against the segment's own
  // neighbours, not the plane, so that a seed plane still turned by its first few points grows.
  // Points of other segments (the wall along a floor's edge) are left out; with fewer than
  // kMinContinuityPoints on either side there is nothing to compare.
  bool continuesSurface(const CellState& state, const Eigen::Vector3d& p, std::uint32_t segment) const {
    if (options_.continuity <= 0.0) return true;
    const Plane& plane = planes_[segment];
    const double window = 2.0 * thresholds_[segment];
    double free_sum = 0.0;
    double own_sum = 0.0;
    std::uint32_t free_count = 0;
    std::uint32_t own_count = 0;
    grid_.forEachAround(p, [&](const GridKey& key) {
      const auto it = state.by_grid.find(key);
      if (it == state.by_grid.end()) return;
      for (std::uint32_t j : it->second) {
        const std::uint8_t owner = state.assigned[j];
        if (owner != 0 && owner != segment + 1) continue;
        if ((state.points[j] - p).squaredNorm() > radius_ * radius_) continue;
        const double d = plane.signedDistance(state.points[j]);
        if (std::abs(d) >= window) continue;
        if (owner == 0) {
          free_sum += d;
          ++free_count;
        } else {
          own_sum += d;
          ++own_count;
        }
      }
    });
    if (free_count < kMinContinuityPoints || own_count < kMinContinuityPoints) return true;
    return std::abs(free_sum / free_count - own_sum / own_count) <= options_.continuity * thresholds_[segment];
  }

  void refit(std::uint32_t segment) {
    ++plane_epoch_;
    planes_[segment] = regressions_[segment].fit();
    fitted_count_[segment] = regressions_[segment].count();
    updateThreshold(segment);
  }

  // A point joins a segment within t_p of its plane, or within noise_sigmas times the plane's
  // RMS where that is tighter (but never below min_threshold_fraction t_p). t_p is the user's
  // precision; the RMS is what the scanner's noise is. Points of a neighbouring surface that lie
  // within t_p of the plane, the bottom strip of a stair riser beside its tread, say, would
  // otherwise join, tilt the plane towards that surface and let the growth creep up it.
  void updateThreshold(std::uint32_t segment) {
    const double tp = parameters_.plane_threshold_m;
    double threshold = tp;
    if (options_.noise_sigmas > 0.0 && planes_[segment].valid) {
      threshold = std::clamp(options_.noise_sigmas * planes_[segment].rms, options_.min_threshold_fraction * tp, tp);
    }
    thresholds_[segment] = threshold;
  }

  // --- results --------------------------------------------------------------------------------

  // Fills the snapshot; outlines and features are redrawn where the segments have grown enough
  // since they were last drawn (everything when `final`).
  void fillSnapshot(bool final) {
    snapshot_.segments.resize(regressions_.size());
    outlined_count_.resize(regressions_.size(), 0);
    std::uint64_t total = 0;
    for (std::size_t s = 0; s < regressions_.size(); ++s) {
      SegmentSnapshot& segment = snapshot_.segments[s];
      segment.plane = planes_[s];
      segment.points = segment_points_[s].size();
      total += segment.points;
      if (!planes_[s].valid) {
        segment.outline.reset();
      } else if (final || segment.points >= outlined_count_[s] + outlined_count_[s] / 4 + 1) {
        OutlineOptions outline;
        outline.alpha_m = radius_;
        outline.cell_m = radius_ / 2.0;
        segment.outline = std::make_shared<const PlaneOutline>(outlineOnPlane(planes_[s], segment_points_[s], outline));
        outlined_count_[s] = segment.points;
      }
    }
    if (final || total >= featured_total_ + featured_total_ / 4 + 1) {
      std::vector<SegmentGeometry> geometry;
      for (std::size_t s = 0; s < regressions_.size(); ++s) geometry.push_back({planes_[s], segment_points_[s]});
      FeatureOptions features;
      features.search_radius = radius_;
      Features found = findEdgesAndCorners(geometry, features);
      snapshot_.edges = std::move(found.edges);
      snapshot_.corners = std::move(found.corners);
      featured_total_ = total;
    }
    snapshot_.mean_neighbour_distance =
        neighbour_distance_count_ > 0 ? neighbour_distance_sum_ / static_cast<double>(neighbour_distance_count_) : 0.0;
    snapshot_.front_spacing_m = front_spacing_;
    snapshot_.elapsed_ms = std::chrono::duration<double, std::milli>(Clock::now() - start_).count();
  }

  void publish() {
    fillSnapshot(false);
    if (progress_) progress_(snapshot_);
  }

  // Settles the points where segments meet: a point went to the first segment that reached it,
  // but near an edge it may lie nearer the plane of the other one. Where one segment got there
  // first along a whole edge, it holds a strip of its neighbour's points there, all on one side
  // of its plane: a bias that grows with the noise. Each point moves to the nearest plane among
  // those of the segments with a point within r of it and within their thresholds; then the
  // regressions are rebuilt from their points.
  void settle() {
    const std::size_t n = regressions_.size();
    if (n < 2) return;
    std::vector<std::vector<Eigen::Vector3d>> points(n);
    std::vector<std::vector<lod::PointRef>> refs(n);
    bool moved = false;
    for (std::uint32_t s = 0; s < n; ++s) {
      for (std::size_t i = 0; i < segment_points_[s].size(); ++i) {
        const Eigen::Vector3d& p = segment_points_[s][i];
        std::uint32_t best = s;
        double best_distance = planes_[s].valid ? planes_[s].distance(p) : INFINITY;
        const std::uint32_t near_mask = segmentsNear(p, 1u << s);
        for (std::uint32_t t = 0; t < n; ++t) {
          if (!((near_mask >> t) & 1u) || !planes_[t].valid) continue;
          const double d = planes_[t].distance(p);
          if (d < best_distance && d < thresholds_[t]) {
            best_distance = d;
            best = t;
          }
        }
        moved = moved || best != s;
        points[best].push_back(p);
        refs[best].push_back(segment_refs_[s][i]);
      }
    }
    if (!moved) return;
    for (std::uint32_t s = 0; s < n; ++s) {
      PlaneRegression regression;
      for (const Eigen::Vector3d& p : points[s]) regression.add(p);
      for (const lod::PointRef& ref : refs[s]) membership_.assign(ref, s);
      regressions_[s] = regression;
      refit(s);
    }
    segment_points_ = std::move(points);
    segment_refs_ = std::move(refs);
    rebuildAssigned();
  }

  // The neighbour grid of the segments' points anew, after they changed hands.
  void rebuildAssigned() {
    assigned_.clear();
    for (std::uint32_t s = 0; s < segment_points_.size(); ++s) {
      for (const Eigen::Vector3d& p : segment_points_[s]) addToGrid(p, s);
    }
  }

  // The segments with a point within r of p, as a bit mask, taking those of `known` as near
  // without looking (p's own segment, whose points fill the cells around it).
  std::uint32_t segmentsNear(const Eigen::Vector3d& p, std::uint32_t known) const {
    std::uint32_t mask = known;
    grid_.forEachAround(p, [&](const GridKey& key) {
      const auto it = assigned_.find(key);
      if (it == assigned_.end() || (it->second.segments & ~mask) == 0) return;
      for (const Assigned& a : it->second.points) {
        if (!((mask >> a.segment) & 1u) && (a.position - p).squaredNorm() <= radius_ * radius_) mask |= 1u << a.segment;
      }
    });
    return mask;
  }

  // The segments that surround p: those whose points within r of it lie around it on their plane,
  // not to one side (their mean, projected on the plane, is within kInsideOffset r of p), as bit
  // mask. A point the growth turned away inside a segment is a tail of its noise; one beside
  // the segment's border is as likely the strip of a surface that meets it there, the ceiling
  // along a wall's top, all on one side of the plane.
  std::uint32_t segmentsAround(const Eigen::Vector3d& p) const {
    std::array<Eigen::Vector3d, kMaxSegments> sum;
    sum.fill(Eigen::Vector3d::Zero());
    std::array<std::uint32_t, kMaxSegments> count{};
    std::uint32_t near = 0;
    grid_.forEachAround(p, [&](const GridKey& key) {
      const auto it = assigned_.find(key);
      if (it == assigned_.end()) return;
      for (const Assigned& a : it->second.points) {
        if ((a.position - p).squaredNorm() > radius_ * radius_) continue;
        near |= 1u << a.segment;
        sum[a.segment] += a.position - p;
        ++count[a.segment];
      }
    });
    std::uint32_t inside = 0;
    for (std::uint32_t s = 0; s < regressions_.size(); ++s) {
      if (!((near >> s) & 1u) || count[s] < kMinAroundPoints || !planes_[s].valid) continue;
      const Eigen::Vector3d mean = sum[s] / static_cast<double>(count[s]);
      const Eigen::Vector3d along = mean - planes_[s].normal.dot(mean) * planes_[s].normal;
      if (along.norm() < kInsideOffset * radius_) inside |= 1u << s;
    }
    return inside;
  }

  // The robust final fit (robust_plane_fit.h). The pool: the segments' points, each with the
  // segments near it, and the points of the processed cells that the growth tested and turned
  // away, where they lie inside a segment (segmentsAround). Each
  // round gives every pool point to the nearest plane, among the near segments', whose window
  // (refine_c times that segment's robust scale) holds it, weighs it by the biweight and refits
  // the planes; the scales follow the points each segment holds. The segments' points become those
  // of positive weight: a point may join that the growth turned away, or leave. A last fit weighs
  // the points inside each segment by 1.
  void refine() {
    const std::size_t n = regressions_.size();
    struct PoolPoint {
      Eigen::Vector3d position;
      lod::PointRef ref;
      std::uint32_t near;  // bit s: the point may go to segment s (near it, or inside it)
    };
    std::vector<PoolPoint> pool;
    std::vector<double> scales(n, 0.0);
    for (std::uint32_t s = 0; s < n; ++s) {
      std::vector<double> residuals;
      for (std::size_t i = 0; i < segment_points_[s].size(); ++i) {
        const Eigen::Vector3d& p = segment_points_[s][i];
        pool.push_back({p, segment_refs_[s][i], segmentsNear(p, 1u << s)});
        if (planes_[s].valid) residuals.push_back(planes_[s].distance(p));
      }
      scales[s] = robustScale(std::move(residuals));
    }
    for (const auto& [key, state] : cells_) {
      if (!state.processed) continue;
      for (std::uint32_t i = 0; i < state.points.size(); ++i) {
        // A point never tested was never within r of a segment's point: not around any segment.
        if (state.assigned[i] || state.rejected_epoch[i] == kNeverTested) continue;
        const std::uint32_t inside = segmentsAround(state.points[i]);
        if (inside != 0) pool.push_back({state.points[i], state.refs[i], inside});
      }
    }

    std::vector<std::int8_t> owner(pool.size(), -1);
    std::vector<double> weights(pool.size(), 0.0);
    // The pool points each segment holds (positive weight), with their weights.
    struct Held {
      std::vector<Eigen::Vector3d> points;
      std::vector<double> weights;
    };
    const auto held = [&] {
      std::vector<Held> result(n);
      for (std::size_t i = 0; i < pool.size(); ++i) {
        if (owner[i] < 0 || !(weights[i] > 0.0)) continue;
        Held& segment = result[static_cast<std::size_t>(owner[i])];
        segment.points.push_back(pool[i].position);
        segment.weights.push_back(weights[i]);
      }
      return result;
    };
    for (std::uint32_t round = 0; round < options_.refine_rounds; ++round) {
      std::vector<std::vector<double>> residuals(n);
      for (std::size_t i = 0; i < pool.size(); ++i) {
        owner[i] = -1;
        weights[i] = 0.0;
        double best = INFINITY;
        for (std::uint32_t s = 0; s < n; ++s) {
          if (!((pool[i].near >> s) & 1u) || !planes_[s].valid) continue;
          const double d = planes_[s].distance(pool[i].position);
          const double window = options_.refine_c * scales[s];
          if (d < window && d < best) {
            best = d;
            owner[i] = static_cast<std::int8_t>(s);
            weights[i] = biweight(d, window);
          }
        }
        if (owner[i] >= 0) residuals[static_cast<std::size_t>(owner[i])].push_back(best);
      }
      const std::vector<Held> segments = held();
      for (std::uint32_t s = 0; s < n; ++s) {
        const Plane fitted = fitWeightedPlane(segments[s].points, segments[s].weights);
        if (!fitted.valid) continue;  // too few points left: the settled plane stays
        planes_[s] = fitted;
        scales[s] = robustScale(std::move(residuals[s]));
      }
    }

    // The last fit gives the points inside each segment full weight: there the biweight only
    // costs efficiency (86 %), while the strips of the surfaces that meet a plane, all on one
    // side of it, lie along its border, where the biweight's weights stay.
    std::vector<Held> members = held();
    for (std::uint32_t s = 0; s < n; ++s) {
      const std::vector<bool> interior = interiorPoints(planes_[s], members[s].points, radius_);
      for (std::size_t j = 0; j < interior.size(); ++j) {
        if (interior[j]) members[s].weights[j] = 1.0;
      }
      const Plane fitted = fitWeightedPlane(members[s].points, members[s].weights);
      if (fitted.valid) planes_[s] = fitted;
    }
    for (auto& list : segment_points_) list.clear();
    for (auto& list : segment_refs_) list.clear();
    for (std::size_t i = 0; i < pool.size(); ++i) {
      if (owner[i] < 0 || !(weights[i] > 0.0)) {
        membership_.release(pool[i].ref);
        continue;
      }
      const auto s = static_cast<std::uint32_t>(owner[i]);
      membership_.assign(pool[i].ref, s);
      segment_points_[s].push_back(pool[i].position);
      segment_refs_[s].push_back(pool[i].ref);
    }
  }

  GrowSnapshot finish(bool converged) {
    if (converged && options_.settle) settle();
    if (converged && options_.refine_c > 0.0) refine();
    snapshot_.converged = converged;
    fillSnapshot(true);
    if (options_.collect_members) {
      auto members = membership_.members(regressions_.size());
      for (std::size_t s = 0; s < members.size(); ++s) snapshot_.segments[s].members = std::move(members[s]);
    }
    return snapshot_;
  }

  static constexpr std::uint64_t kMinFrontSamples = 16;
  static constexpr std::uint32_t kNeverTested = ~std::uint32_t{0};
  static constexpr std::size_t kMaxSegments = 32;  // segment masks are 32 bits wide
  // segmentsAround: a point on a segment's border has the segment's points to one side, their
  // mean 4 / (3 pi) = 0.42 r from it (a half disc); inside, a dozen points' mean strays about
  // 0.18 r. 0.3 r keeps nine in ten inside and a fifth of those on the border.
  static constexpr double kInsideOffset = 0.3;
  static constexpr std::uint32_t kMinAroundPoints = 4;
  static constexpr std::uint32_t kMinContinuityPoints = 4;
  // A floor seen at grazing angles needs a bridge per scan line until it reaches denser ground;
  // this bounds the work where a segment keeps finding a point or two beyond r.
  static constexpr std::uint32_t kMaxBridges = 32;

  lod::NodeCache& cache_;
  const lod::Octree& octree_;
  GrowParameters parameters_;
  GrowOptions options_;
  const GrowProgress& progress_;
  double radius_;  // r: the parameters', or wider where the data is sparser (adaptToDataSpacing)
  PointGrid grid_;
  CellClaims claims_;
  Membership membership_;
  Clock::time_point start_;
  std::uint32_t base_level_ = 0;
  std::uint32_t working_level_ = 0;  // the level new cells are claimed at

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
  std::unordered_map<GridKey, AssignedCell, GridKeyHash> assigned_;
  std::priority_queue<std::pair<double, CellKey>, std::vector<std::pair<double, CellKey>>, std::greater<>> queue_;
  std::unordered_set<CellKey, lod::CellKeyHash> queued_;
  std::optional<CellKey> processing_;  // the cell whose breadth-first search is running
  std::optional<lod::Box3> processing_box_;
  std::uint32_t plane_epoch_ = 0;  // counts the refits: a rejected point's test holds until the next
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

}  // namespace

GrowSnapshot growRegions(lod::NodeCache& cache, const GrowParameters& parameters, const GrowOptions& options,
                         const GrowProgress& progress) {
  return Grower(cache, parameters, options, progress).run();
}

}  // namespace plumb::reco
