// The grower's cells (region_grower.cpp, steps 3 and 4): loading and claiming octree cells,
// handing the frontier to the neighbouring cells, and the adaptive resolution of paper
// section 3.6 (refine a cell into its children, mark and finish a level before coarsening).

#include <algorithm>
#include <map>

#include "reco/grower.h"

namespace plumb::reco::detail {

CellState& Grower::loaded(const CellKey& key) {
  CellState& state = cells_[key];
  if (!state.loaded) {
    state.loaded = true;
    const std::vector<lod::CellPoint> points = cell_points_.pointsInCell(key, key.level + point_levels_);
    state.reserve(points.size());
    for (const lod::CellPoint& p : points) {
      const Eigen::Vector3d position(p.position[0], p.position[1], p.position[2]);
      if (options_.keep && !options_.keep(position)) continue;  // cut away by the view's section
      state.add(position, p.ref, membership_.flag(p.ref));
    }
    if (!gathering_seed_) indexCell(state);  // the seed indexes its cells once r is known
  }
  return state;
}

// A cell's search radius (paper section 3.7: twice the mean point spacing, here the cell's).
// r comes from the seed's spacing, and at full detail every point is taken: where the growth
// reaches surfaces nearer the scanner, many times denser, a search within r met (r / s)^2 times
// the points it needs, and the cost of a grown point grew with the density (a 1 M-point room,
// floor spacing 11 mm against r = 54 mm: 200 points looked at per search). The cell's areal
// spacing, from the median count of its points per r-wide grid cell (a surface crossing the
// cell's r-cubes has about r^2 of area in each), sets its radius where it is less than half
// of r (never below r / 8). Only where r came from the seed's data spacing (adaptToDataSpacing:
// full detail, or a sparse scan), not from d: a cell denser than d asks is the octree's to thin,
// and at medium detail the cell keeps r. A point of a sparser surface in such a cell (a wall's
// far face, scanned from afar) is searched within r still (processCell).
void Grower::indexCell(CellState& state) const {
  state.index(radius_, parameters_.seed);
  if (!radius_from_data_) return;
  const std::uint32_t per_cell = state.by_grid.medianCellPoints();
  if (per_cell == 0) return;
  const double spacing = radius_ / std::sqrt(static_cast<double>(per_cell));
  const double radius = std::max(reachFor(spacing), radius_ / kMaxRadiusShrink);
  if (radius >= 0.5 * radius_) return;
  state.index(radius, parameters_.seed);
}

void Grower::enqueue(const CellKey& key) {
  if (!queued_.insert(key).second) return;
  queue_.push({octree_.cube().squaredDistance(key, array(parameters_.seed)), key});
}

// Hands p, a point of cell `holder`, to the frontier of every claimed cell within r of it other
// than the one being processed (whose breadth-first search has p already), claiming cells where
// none is yet. Outside processCell (the seed, a bridge) p's own cell gets it too, and is queued
// with its first frontier point: no cell waits for a level then, so one with a frontier is
// queued already (the seed hands over every inlier this way).
void Grower::spreadFrontier(const Eigen::Vector3d& p, std::uint32_t segment, const CellKey& holder,
                            CellState& holder_state) {
  // Cells are at least 8 search radii wide: only the sides of the box of p's cell that p is
  // within r of lead to a neighbour (the other offsets land in p's cell or in a neighbour
  // found already).
  const lod::Box3 box = octree_.cube().cellBox(holder);
  std::array<std::array<int, 3>, 3> steps{};  // per axis: the offsets to try, -1, 0 or +1
  std::array<std::size_t, 3> step_count{};
  for (std::size_t a = 0; a < 3; ++a) {
    steps[a][step_count[a]++] = 0;
    if (p[static_cast<Eigen::Index>(a)] - radius_ <= box.min[a]) steps[a][step_count[a]++] = -1;
    if (p[static_cast<Eigen::Index>(a)] + radius_ >= box.max[a]) steps[a][step_count[a]++] = 1;
  }
  if (processing_ && step_count[0] * step_count[1] * step_count[2] == 1) return;
  std::array<CellKey, 27> seen;
  std::size_t count = 0;
  for (std::size_t iz = 0; iz < step_count[2]; ++iz) {
    for (std::size_t iy = 0; iy < step_count[1]; ++iy) {
      for (std::size_t ix = 0; ix < step_count[0]; ++ix) {
        if (ix == 0 && iy == 0 && iz == 0) {  // steps[a][0] is 0: p's own cell, the first
          seen[count++] = holder;
          if (processing_) continue;
          if (holder_state.frontier.empty()) enqueue(holder);
          holder_state.frontier.push_back({p, segment});
          continue;
        }
        bool created = false;
        const CellKey key =
            claims_.claimAt(array(p + radius_ * Eigen::Vector3d(steps[0][ix], steps[1][iy], steps[2][iz])),
                            working_level_, octree_.header().depth, created);
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

// The observed areal density relative to the wanted one; nullopt until enough points tell.
std::optional<double> Grower::densityRatio() const {
  if (front_samples_ < kMinFrontSamples || front_spacing_ <= 0.0) return std::nullopt;
  const double ratio = parameters_.spacing_m / front_spacing_;
  return ratio * ratio;
}

// Applies the adaptive resolution to `key` as it leaves the queue. Returns true when the cell
// is not to be processed now (replaced, or waiting for a level change).
bool Grower::adapt(const CellKey& key) {
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
  if (*ratio < options_.refine_below && !cells_[key].processed && key.level + point_levels_ < octree_.header().depth &&
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

void Grower::replaceByChildren(const CellKey& key) {
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
void Grower::lockLevel(std::uint32_t level) {
  locked_level_ = level;
  marked_parents_.clear();
  for (const CellKey& key : claims_.cells()) {
    if (key.level == level) marked_parents_.insert(*key.parent());
  }
}

// Finish: the marked cells are done; each group of waiting cells moves to its parent if the
// density is still too high there and nothing inside that parent was processed.
void Grower::unlockLevel() {
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
bool Grower::canMerge(const CellKey& parent) {
  for (const CellKey& child : parent.children()) {
    if (claims_.claimedBelow(child)) return false;
    if (claims_.claimed(child) && cells_[child].processed) return false;
  }
  return true;
}

}  // namespace plumb::reco::detail
