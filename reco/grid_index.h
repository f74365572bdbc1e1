#pragma once
// A fixed set of points bucketed by the cells of a PointGrid, for the neighbour searches of the
// region grower inside one octree cell: which points lie in a grid cell, in ascending index order.
// Built once (the points of an octree cell do not change during a grow); a lookup is one probe
// sequence in a flat open-addressing table and the indices are contiguous, where a hash map of
// vectors cost two or three cache misses per grid cell, 27 cells per search.

#include <Eigen/Core>
#include <cstdint>
#include <span>
#include <vector>

#include "engine/core/bucket_index.h"
#include "reco/point_grid.h"

namespace plumb::reco {

class GridIndex {
 public:
  GridIndex() = default;
  // Buckets `points` (at most 2^32 - 1) by grid.keyOf. O(n).
  GridIndex(const PointGrid& grid, std::span<const Eigen::Vector3d> points);

  // The median number of points in the grid cells that hold any (0 for no point).
  std::uint32_t medianCellPoints() const { return median_cell_points_; }

  // The indices of the points in grid cell `key`, ascending; empty when none.
  std::span<const std::uint32_t> at(const GridKey& key) const { return cells_.at(key); }

  // The points of grid cell `key`: their indices as at() gives them, where the run starts in
  // order(), and, in the same order, their positions relative to the grid's origin in single
  // precision, one array per axis. A scan of every point in the cells around one reads them one
  // after another instead of at random, and in vector registers (the grower's continuity test).
  struct Bucket {
    std::span<const std::uint32_t> indices;
    std::uint32_t first = 0;  // indices[k] is order()[first + k]
    std::span<const float> x, y, z;
  };
  Bucket bucket(const GridKey& key) const {
    const auto* run = cells_.find(key);
    if (run == nullptr) return {};
    const std::size_t size = run->end - run->begin;
    return {cells_.items(*run), run->begin, std::span(x_.data() + run->begin, size),
            std::span(y_.data() + run->begin, size), std::span(z_.data() + run->begin, size)};
  }

  // Every point's index, grouped by grid cell (the cells in no particular order).
  const std::vector<std::uint32_t>& order() const { return cells_.order(); }

 private:
  BucketIndex<GridKey, GridKeyLowBitsHash> cells_;
  // The points' positions relative to the grid's origin, as cells_.order().
  std::vector<float> x_, y_, z_;
  std::uint32_t median_cell_points_ = 0;
};

}  // namespace plumb::reco
