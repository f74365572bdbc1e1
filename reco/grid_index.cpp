#include "reco/grid_index.h"

#include <algorithm>
#include <bit>
#include <cassert>

namespace plumb::reco {

// In O(n): each point's grid cell is found in (or entered into) a table sized for every point
// being alone in its cell, which numbers the cells in order of their first point; a count per
// cell and its prefix sums place each point, in ascending order, in its cell's run of order_;
// the runs then go into a table sized for the cells. (Sorting the points by key did the same
// in O(n log n), and was a twentieth of a full-detail grow: the grower indexes every cell it
// loads.)
GridIndex::GridIndex(const PointGrid& grid, std::span<const Eigen::Vector3d> points) {
  assert(points.size() < 0xFFFFFFFFu && "a grid index holds at most 2^32 - 1 points");
  if (points.empty()) return;
  struct Numbered {
    GridKey key{0, 0, 0};
    std::uint32_t cell = 0;  // 0: an empty slot; otherwise the cell's number + 1
  };
  std::vector<Numbered> numbering(std::bit_ceil(2 * points.size()));
  const std::size_t numbering_mask = numbering.size() - 1;
  std::vector<std::uint32_t> cell_of(points.size());
  std::vector<Slot> cells;  // per cell: its key, then its run in order_
  for (std::uint32_t i = 0; i < points.size(); ++i) {
    const GridKey key = grid.keyOf(points[i]);
    std::size_t slot = lowBitsHash(key) & numbering_mask;
    while (numbering[slot].cell != 0 && !(numbering[slot].key == key)) slot = (slot + 1) & numbering_mask;
    if (numbering[slot].cell == 0) {
      cells.push_back({key, 0, 0});
      numbering[slot] = {key, static_cast<std::uint32_t>(cells.size())};
    }
    cell_of[i] = numbering[slot].cell - 1;
    ++cells[cell_of[i]].end;  // the count, for now
  }
  std::vector<std::uint32_t> sizes;
  sizes.reserve(cells.size());
  for (const Slot& cell : cells) sizes.push_back(cell.end);
  const auto middle = sizes.begin() + static_cast<std::ptrdiff_t>(sizes.size() / 2);
  std::nth_element(sizes.begin(), middle, sizes.end());
  median_cell_points_ = *middle;

  std::uint32_t begin = 0;
  for (Slot& cell : cells) {
    const std::uint32_t count = cell.end;
    cell.begin = cell.end = begin;  // end advances as the points are placed
    begin += count;
  }
  order_.resize(points.size());
  offsets_.resize(points.size());
  for (std::uint32_t i = 0; i < points.size(); ++i) {
    const std::uint32_t k = cells[cell_of[i]].end++;
    order_[k] = i;
    offsets_[k] = (points[i] - grid.origin()).cast<float>();
  }

  slots_.assign(std::bit_ceil(2 * cells.size()), Slot{});
  mask_ = slots_.size() - 1;
  for (const Slot& cell : cells) {
    std::size_t slot = lowBitsHash(cell.key) & mask_;
    while (slots_[slot].end != 0) slot = (slot + 1) & mask_;
    slots_[slot] = cell;
  }
}

}  // namespace plumb::reco
