#include "reco/grid_index.h"

#include <algorithm>

namespace plumb::reco {

GridIndex::GridIndex(const PointGrid& grid, std::span<const Eigen::Vector3d> points) {
  std::vector<GridKey> keys(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) keys[i] = grid.keyOf(points[i]);
  cells_ = BucketIndex<GridKey, GridKeyLowBitsHash>(keys);
  x_.reserve(points.size());
  y_.reserve(points.size());
  z_.reserve(points.size());
  for (std::uint32_t i : cells_.order()) {
    const Eigen::Vector3f offset = (points[i] - grid.origin()).cast<float>();
    x_.push_back(offset.x());
    y_.push_back(offset.y());
    z_.push_back(offset.z());
  }
  std::vector<std::uint32_t> sizes;
  cells_.forEachRun([&](const auto& run) { sizes.push_back(run.end - run.begin); });
  if (sizes.empty()) return;
  const auto middle = sizes.begin() + static_cast<std::ptrdiff_t>(sizes.size() / 2);
  std::nth_element(sizes.begin(), middle, sizes.end());
  median_cell_points_ = *middle;
}

}  // namespace plumb::reco
