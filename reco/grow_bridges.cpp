// Bridges (region_grower.cpp, step 6): where the growth stops, a segment may cross a gap wider
// than r to the free points on its plane within r_s / 2 of it, and the growth goes on from them.

#include <algorithm>

#include "reco/grower.h"

namespace plumb::reco::detail {

// Where the growth has stopped, a segment may be stuck at a gap wider than r that the seed's
// scale does not see: the scan lines of a floor seen at grazing angles, farther apart than the
// points of the walls beside it (whose spacing sets r), or the shadow of a cabinet leg. Each
// segment takes the free points within half the seed radius of its points that lie within its
// threshold and that no segment within r of them accepts (the continuity test's rejects stay
// out); the growth goes on from them at r. Returns whether any segment took a point.
bool Grower::bridgeGaps() {
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

// One bridge from segment s: the free points within `reach` of its points that join it.
bool Grower::bridge(std::uint32_t s, double reach) {
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
  for (const auto& [key, i] : taken) assign(key, cells_[key], i, s);
  if (!taken.empty()) refit(s);
  return !taken.empty();
}

// The cells that may hold points within `reach` of the points in the `coarse` grid cells
// `own` (a grid of step `reach`): those the grid cells' boxes, widened by reach, meet, claimed
// at the working level where none is claimed yet. Sorted, so that the points join in the same
// order whatever the hashing.
std::vector<CellKey> Grower::cellsWithinReach(const PointsByGridCell& own, const PointGrid& coarse, double reach) {
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

}  // namespace plumb::reco::detail
