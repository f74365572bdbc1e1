#include "reco/grid_index.h"

#include <algorithm>
#include <bit>
#include <cassert>
#include <tuple>

namespace plumb::reco {

GridIndex::GridIndex(const PointGrid& grid, std::span<const Eigen::Vector3d> points) {
  assert(points.size() < 0xFFFFFFFFu && "a grid index holds at most 2^32 - 1 points");
  struct Keyed {
    GridKey key;
    std::uint32_t index;
  };
  std::vector<Keyed> keyed(points.size());
  for (std::uint32_t i = 0; i < points.size(); ++i) keyed[i] = {grid.keyOf(points[i]), i};
  std::sort(keyed.begin(), keyed.end(), [](const Keyed& a, const Keyed& b) {
    return std::tie(a.key.x, a.key.y, a.key.z, a.index) < std::tie(b.key.x, b.key.y, b.key.z, b.index);
  });
  order_.resize(keyed.size());
  std::vector<Slot> buckets;
  for (std::uint32_t i = 0; i < keyed.size(); ++i) {
    order_[i] = keyed[i].index;
    if (i == 0 || !(keyed[i].key == keyed[i - 1].key)) buckets.push_back({keyed[i].key, i, i});
    buckets.back().end = i + 1;
  }
  if (buckets.empty()) return;
  std::vector<std::uint32_t> sizes;
  sizes.reserve(buckets.size());
  for (const Slot& bucket : buckets) sizes.push_back(bucket.end - bucket.begin);
  const auto middle = sizes.begin() + static_cast<std::ptrdiff_t>(sizes.size() / 2);
  std::nth_element(sizes.begin(), middle, sizes.end());
  median_cell_points_ = *middle;
  slots_.assign(std::bit_ceil(2 * buckets.size()), Slot{});
  mask_ = slots_.size() - 1;
  for (const Slot& bucket : buckets) {
    std::size_t slot = lowBitsHash(bucket.key) & mask_;
    while (slots_[slot].end != 0) slot = (slot + 1) & mask_;
    slots_[slot] = bucket;
  }
}

}  // namespace plumb::reco
