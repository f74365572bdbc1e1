#include "engine/render/intensity_range.h"

#include <algorithm>
#include <cstdint>
#include <vector>

#include "engine/core/error.h"
#include "engine/lod/node_cache.h"

namespace plumb::render {

IntensityRange sampleIntensityRange(lod::NodeCache& nodes, std::size_t sample_points) {
  std::vector<std::uint16_t> sample;
  try {
    for (const lod::NodeInfo& node : nodes.octree().nodes()) {
      if (sample.size() >= sample_points) break;
      if (node.point_count == 0) continue;  // a COPC inner node may hold none
      const auto points = nodes.get(node.key);
      if (!points) continue;
      for (const lod::PackedPoint& point : points->points) sample.push_back(point.intensity);
    }
  } catch (const Error&) {
    return {};
  }
  if (sample.empty()) return {};
  const auto at = [&](double share) {
    const auto k = static_cast<std::ptrdiff_t>(share * static_cast<double>(sample.size() - 1));
    std::nth_element(sample.begin(), sample.begin() + k, sample.end());
    return sample[static_cast<std::size_t>(k)];
  };
  const std::uint16_t low = at(0.01), high = at(0.99);
  if (high <= low) return {};
  return {static_cast<float>(low), static_cast<float>(high)};
}

}  // namespace plumb::render
