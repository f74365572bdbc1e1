// The growth point by point (paper section 3.5; region_grower.cpp, step 3): the inlier test of a
// free point against the planes of the segments within r of it, the continuity test, the
// breadth-first search of a cell from its frontier, and the refits and thresholds that follow.

#include <algorithm>
#include <cmath>
#include <optional>

#include "reco/continuity_scan.h"
#include "reco/grower.h"

namespace plumb::reco::detail {

// Enters a segment's point in the neighbour grid.
void Grower::addToGrid(const Eigen::Vector3d& p, std::uint32_t segment) {
  AssignedCell& cell = assigned_[grid_.keyOf(p)];
  cell.segments |= 1u << segment;
  cell.points.push_back({p, segment});
}

// Records point `index` of cell `key` as joining `segment`.
void Grower::assign(const CellKey& key, CellState& state, std::uint32_t index, std::uint32_t segment) {
  membership_.assign(state.refs[index], segment);
  state.join(index, static_cast<std::uint8_t>(segment + 1));
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
  spreadFrontier(p, segment, key, state);
}

// The segment an unassigned point p joins: the nearest plane within its threshold among the segments
// with an assigned point within r of p; and how far the nearest assigned point is.
// `measure`: also find the nearest assigned point (what the adaptive resolution observes), at
// the cost of a distance to every assigned point of the cells around that may hold a nearer
// one (p's own cell first); otherwise each segment's first point within r ends its search.
// `known`: an assigned point within r of p that the caller has at hand (the frontier point p
// was found from); its segment is tested first, and cells holding no other segment are passed
// over without a look at their points.
Candidate Grower::bestSegment(const Eigen::Vector3d& p, bool measure, const std::optional<KnownNeighbour>& known) {
  Candidate best;
  double best_distance = INFINITY;
  double nearest2 = INFINITY;
  std::uint32_t seen_mask = 0;
  const double radius2 = radius_ * radius_;
  auto test = [&](std::uint32_t segment) {
    seen_mask |= 1u << segment;
    ++snapshot_.points_tested;
    const Plane& plane = planes_[segment];
    if (!plane.valid) return;
    best.tested |= 1u << segment;
    const double d = plane.distance(p);
    if (d < thresholds_[segment] && d < best_distance) {
      best_distance = d;
      best.segment = static_cast<int>(segment);
    }
  };
  if (known) {
    nearest2 = known->distance2;
    test(known->segment);
  }
  grid_.forEachNear(p, [&](const GridKey& key) {
    const AssignedCell* cell = assigned_.find(key);
    if (cell == nullptr) return;
    const double cell_distance2 = grid_.squaredDistanceToCell(p, key);
    if (cell_distance2 > radius2) return;
    const bool unseen = (cell->segments & ~seen_mask) != 0;
    if (!unseen && (!measure || cell_distance2 >= nearest2)) return;
    for (const Assigned& a : cell->points) {
      if (!measure && ((seen_mask >> a.segment) & 1u)) {
        if ((cell->segments & ~seen_mask) == 0) break;  // each of the cell's segments seen
        continue;
      }
      const double d2 = (a.position - p).squaredNorm();
      if (d2 > radius2) continue;
      nearest2 = std::min(nearest2, d2);
      if (!((seen_mask >> a.segment) & 1u)) test(a.segment);
    }
  });
  best.nearest_m = std::sqrt(nearest2);
  return best;
}

void Grower::observeSpacing(double nearest_m) {
  // A running mean over the last few dozen measured points: the density where the front is now.
  constexpr double kWeight = 1.0 / 32.0;
  front_spacing_ = front_samples_ == 0 ? nearest_m : front_spacing_ + kWeight * (nearest_m - front_spacing_);
  ++front_samples_;
}

// Breadth-first from the cell's frontier; returns whether any point was added. A point that
// joins has just had its neighbours scanned by the continuity test, which lists the free ones
// within the cell's radius; the search from that point walks the list instead of the grid
// (the two scans were half of a full-detail grow). Points from the frontier, or every point
// where the continuity test is off, are searched in the grid. The order is the grid's either
// way, so the result is the same.
bool Grower::processCell(const CellKey& key) {
  ++snapshot_.cells_visited;
  snapshot_.finest_level = std::max(snapshot_.finest_level, key.level + point_levels_);
  snapshot_.coarsest_level = std::min(snapshot_.coarsest_level, key.level + point_levels_);
  processing_ = key;
  working_level_ = key.level;  // new neighbours start at this cell's level
  CellState& state = loaded(key);
  state.processed = true;
  struct NeighbourRun {
    std::uint32_t begin = 0;
    std::uint32_t end = 0;
    std::uint32_t around = 0;  // the point's own surface's points and free ones within the radius, itself too
  };
  struct Queued {
    Assigned from;
    std::optional<NeighbourRun> free_around;  // its run of `listed`, where the continuity test made one
  };
  std::vector<Queued> queue;
  for (const Assigned& a : state.frontier) queue.push_back({a, std::nullopt});
  state.frontier.clear();
  std::vector<std::uint32_t> listed;
  bool added = false;
  const double radius2 = state.radius * state.radius;
  auto visit = [&](const Assigned& from, std::uint32_t i, double distance2) {
    if (state.rejected_epoch[i] == plane_epoch_ && ((state.rejected_by[i] >> from.segment) & 1u)) {
      ++snapshot_.tests_skipped;
      return;
    }
    // One added point in four is measured: enough for a running mean of the spacing.
    const bool measure = (neighbour_distance_count_ & 3u) == 0;
    Candidate candidate = bestSegment(state.points[i], measure, KnownNeighbour{from.segment, distance2});
    const auto listed_before = static_cast<std::uint32_t>(listed.size());
    std::uint32_t around = 0;
    if (candidate.segment >= 0 &&
        !continuesSurface(state, state.points[i], static_cast<std::uint32_t>(candidate.segment), &listed, &around)) {
      candidate.segment = -1;
    }
    if (candidate.segment < 0) {
      listed.resize(listed_before);  // nothing is searched from a point that stays free
      state.rejected_epoch[i] = plane_epoch_;
      state.rejected_by[i] = candidate.tested;
      return;
    }
    assign(key, state, i, static_cast<std::uint32_t>(candidate.segment));
    std::optional<NeighbourRun> free_around;
    if (options_.continuity > 0.0) {
      free_around = NeighbourRun{listed_before, static_cast<std::uint32_t>(listed.size()), around};
    }
    queue.push_back({{state.points[i], static_cast<std::uint32_t>(candidate.segment)}, free_around});
    neighbour_distance_sum_ += std::sqrt(distance2);
    ++neighbour_distance_count_;
    if (measure) observeSpacing(candidate.nearest_m);
    added = true;
  };
  // Where the cell's radius is less than r (indexCell: its bulk is denser than the seed), a point
  // with few neighbours within it lies on a sparser surface (a wall's face scanned from afar
  // beside its other face scanned up close, in the same cells): its free points within r are
  // visited too, from a grid of r made for the cell on first need, as every point was searched
  // before the cell's radius shrank. Without that, such a surface stopped at its seed.
  const double wide2 = radius_ * radius_;
  const PointGrid wide_grid(parameters_.seed, radius_);
  auto visitWithinR = [&](const Assigned& from) {
    if (!state.by_wide_grid) state.by_wide_grid.emplace(wide_grid, state.points);
    wide_grid.forEachAroundWithin(from.position, radius_, [&](const GridKey& grid_key) {
      for (std::uint32_t i : state.by_wide_grid->at(grid_key)) {
        if (state.assigned[i]) continue;
        const double distance2 = (state.points[i] - from.position).squaredNorm();
        if (distance2 > radius2 && distance2 <= wide2) visit(from, i, distance2);
      }
    });
  };
  const bool shrunk = state.radius < radius_;
  for (std::size_t next = 0; next < queue.size(); ++next) {
    const Assigned from = queue[next].from;
    if (const std::optional<NeighbourRun> run = queue[next].free_around) {
      for (std::uint32_t k = run->begin; k < run->end; ++k) {
        const std::uint32_t i = listed[k];
        if (!state.assigned[i]) visit(from, i, (state.points[i] - from.position).squaredNorm());
      }
      if (shrunk && run->around < kMinShrunkNeighbours + 1) visitWithinR(from);  // +1: the point itself
      continue;
    }
    std::uint32_t around = 0;
    state.grid.forEachAroundWithin(from.position, state.radius, [&](const GridKey& grid_key) {
      for (std::uint32_t i : state.by_grid.at(grid_key)) {
        const std::uint8_t owner = state.assigned[i];
        if (owner != 0 && !(shrunk && owner == from.segment + 1)) continue;
        const double distance2 = (state.points[i] - from.position).squaredNorm();
        if (distance2 > radius2) continue;
        ++around;
        if (owner == 0) visit(from, i, distance2);
      }
    });
    if (shrunk && around < kMinShrunkNeighbours + 1)
      visitWithinR(from);  // +1: the point itself, where it lies in the cell
  }
  processing_.reset();
  if (added) {
    for (std::uint32_t s = 0; s < regressions_.size(); ++s) {
      if (grown_[s]) refit(s);
      grown_[s] = false;
    }
  }
  return added;
}

// Whether the surface around p continues the segment's surface there: the mean offset from the
// plane of the free points within r of p (p included) against that of the segment's own points
// within r, both within twice the threshold, must differ by at most continuity x the threshold.
// A plane test alone lets in the points of a parallel surface a few sigmas behind (a door leaf
// in its recess, at high noise) one in twenty, each pulling the plane towards the rest of it;
// the mean of a dozen neighbours is four times surer than one point. Against the segment's own
// neighbours, not the plane, so that a seed plane still turned by its first few points grows.
// Points of other segments (the wall along a floor's edge) are left out; with fewer than
// kMinContinuityPoints on either side there is nothing to compare. Appends the free points
// within r of p, in the grid's order, to `free_around`, and counts them and the segment's in `around`.
bool Grower::continuesSurface(const CellState& state, const Eigen::Vector3d& p, std::uint32_t segment,
                              std::vector<std::uint32_t>* free_around, std::uint32_t* around) const {
  if (options_.continuity <= 0.0) return true;
  const Plane& plane = planes_[segment];
  const double window = 2.0 * thresholds_[segment];
  ContinuityScan scan;
  // In single precision relative to the grid's origin (GridIndex::bucket): millimetres within
  // micrometres over tens of metres.
  const Eigen::Vector3f at = (p - state.grid.origin()).cast<float>();
  scan.at = {at.x(), at.y(), at.z()};
  scan.normal = {static_cast<float>(plane.normal.x()), static_cast<float>(plane.normal.y()),
                 static_cast<float>(plane.normal.z())};
  scan.origin_offset = static_cast<float>(plane.signedDistance(state.grid.origin()));
  scan.window = static_cast<float>(window);
  scan.radius2 = static_cast<float>(state.radius * state.radius);
  scan.own = static_cast<std::uint8_t>(segment + 1);
  scan.units_per_m = continuityUnitsPerMetre(window);
  ContinuitySums sums;
  state.grid.forEachAroundWithin(p, state.radius, [&](const GridKey& key) {
    const GridIndex::Bucket bucket = state.by_grid.bucket(key);
    if (bucket.indices.empty()) return;
    scanBucket(scan, bucket, std::span(state.assigned_by_grid).subspan(bucket.first, bucket.indices.size()),
               *free_around, sums);
  });
  *around += sums.near;
  if (sums.free_count < kMinContinuityPoints || sums.own_count < kMinContinuityPoints) return true;
  const double free_mean = static_cast<double>(sums.free_sum) / static_cast<double>(sums.free_count);
  const double own_mean = static_cast<double>(sums.own_sum) / static_cast<double>(sums.own_count);
  return std::abs(free_mean - own_mean) / scan.units_per_m <= options_.continuity * thresholds_[segment];
}

void Grower::refit(std::uint32_t segment) {
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
void Grower::updateThreshold(std::uint32_t segment) {
  const double tp = parameters_.plane_threshold_m;
  double threshold = tp;
  if (options_.noise_sigmas > 0.0 && planes_[segment].valid) {
    threshold = std::clamp(options_.noise_sigmas * planes_[segment].rms, options_.min_threshold_fraction * tp, tp);
  }
  thresholds_[segment] = threshold;
}

}  // namespace plumb::reco::detail
