// The growth point by point (paper section 3.5; region_grower.cpp, step 3): the inlier test of a
// free point against the planes of the segments within r of it, the continuity test, the
// breadth-first search of a cell from its frontier, and the refits and thresholds that follow.

#include <algorithm>
#include <cmath>

#include "reco/grower.h"

namespace plumb::reco::detail {

// Enters a segment's point in the neighbour grid.
void Grower::addToGrid(const Eigen::Vector3d& p, std::uint32_t segment) {
  AssignedCell& cell = assigned_[grid_.keyOf(p)];
  cell.segments |= 1u << segment;
  cell.points.push_back({p, segment});
}

// Records point i of a cell as joining `segment`.
void Grower::assign(CellState& state, std::uint32_t index, std::uint32_t segment) {
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

// The segment an unassigned point p joins: the nearest plane within its threshold among the segments
// with an assigned point within r of p; and how far the nearest assigned point is.
// `measure`: also find the nearest assigned point (what the adaptive resolution observes), at
// the cost of a distance to every assigned point of the cells around that may hold a nearer
// one (p's own cell first); otherwise each segment's first point within r ends its search.
Candidate Grower::bestSegment(const Eigen::Vector3d& p, bool measure) {
  Candidate best;
  double best_distance = INFINITY;
  double nearest2 = INFINITY;
  std::uint32_t seen_mask = 0;
  const double radius2 = radius_ * radius_;
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

void Grower::observeSpacing(double nearest_m) {
  // A running mean over the last few dozen measured points: the density where the front is now.
  constexpr double kWeight = 1.0 / 32.0;
  front_spacing_ = front_samples_ == 0 ? nearest_m : front_spacing_ + kWeight * (nearest_m - front_spacing_);
  ++front_samples_;
}

// Breadth-first from the cell's frontier; returns whether any point was added.
bool Grower::processCell(const CellKey& key) {
  ++snapshot_.cells_visited;
  snapshot_.finest_level = std::max(snapshot_.finest_level, key.level + point_levels_);
  snapshot_.coarsest_level = std::min(snapshot_.coarsest_level, key.level + point_levels_);
  processing_ = key;
  processing_box_ = octree_.cube().cellBox(key);
  working_level_ = key.level;  // new neighbours start at this cell's level
  CellState& state = loaded(key);
  state.processed = true;
  std::vector<Assigned> queue = std::move(state.frontier);
  state.frontier.clear();
  bool added = false;
  const double radius2 = state.radius * state.radius;
  for (std::size_t next = 0; next < queue.size(); ++next) {
    const Assigned from = queue[next];
    state.grid.forEachAround(from.position, [&](const GridKey& grid_key) {
      for (std::uint32_t i : state.by_grid.at(grid_key)) {
        if (state.assigned[i]) continue;
        const double distance2 = (state.points[i] - from.position).squaredNorm();
        if (distance2 > radius2) continue;
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
        neighbour_distance_sum_ += std::sqrt(distance2);
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

// Whether the surface around p continues the segment's surface there: the mean offset from the
// plane of the free points within r of p (p included) against that of the segment's own points
// within r, both within twice the threshold, must differ by at most continuity x the threshold.
// A plane test alone lets in the points of a parallel surface a few sigmas behind (a door leaf
// in its recess, at high noise) one in twenty, each pulling the plane towards the rest of it;
// the mean of a dozen neighbours is four times surer than one point. Against the segment's own
// neighbours, not the plane, so that a seed plane still turned by its first few points grows.
// Points of other segments (the wall along a floor's edge) are left out; with fewer than
// kMinContinuityPoints on either side there is nothing to compare.
bool Grower::continuesSurface(const CellState& state, const Eigen::Vector3d& p, std::uint32_t segment) const {
  if (options_.continuity <= 0.0) return true;
  const Plane& plane = planes_[segment];
  const double window = 2.0 * thresholds_[segment];
  double free_sum = 0.0;
  double own_sum = 0.0;
  std::uint32_t free_count = 0;
  std::uint32_t own_count = 0;
  const double radius2 = state.radius * state.radius;
  state.grid.forEachAround(p, [&](const GridKey& key) {
    for (std::uint32_t j : state.by_grid.at(key)) {
      const std::uint8_t owner = state.assigned[j];
      if (owner != 0 && owner != segment + 1) continue;
      if ((state.points[j] - p).squaredNorm() > radius2) continue;
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
