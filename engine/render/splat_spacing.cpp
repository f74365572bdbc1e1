#include "engine/render/splat_spacing.h"

#include <cmath>
#include <unordered_map>

namespace plumb::render {

std::vector<std::array<float, 8>> octantRadiusScales(std::span<const DrawnNode> nodes) {
  std::unordered_map<lod::CellKey, std::size_t, lod::CellKeyHash> index;
  index.reserve(nodes.size());
  for (std::size_t i = 0; i < nodes.size(); ++i) index.emplace(nodes[i].key, i);

  std::vector<std::array<float, 8>> scales(nodes.size());
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    const DrawnNode& node = nodes[i];
    for (int octant = 0; octant < 8; ++octant) {
      const auto o = static_cast<std::size_t>(octant);
      const auto child = index.find(node.key.child(octant));
      // Where the node is the finest drawn, its surfels were measured among the drawn cloud.
      if (child == index.end() || node.octant_points[o] == 0) {
        scales[i][o] = 1.0f;
        continue;
      }
      // Where a child is drawn too: the node's points and its ancestors' there against those and
      // the child's. Each ancestor holds about a quarter of its child's density on a surface: a
      // node of level L measured (1 + 1/4 + ... + 1/4^L) times its own points (the root, none more).
      const double ancestors_share = (1.0 - std::ldexp(1.0, -2 * static_cast<int>(node.key.level))) / 3.0;
      const double measured = (1.0 + ancestors_share) * node.octant_points[o];
      scales[i][o] =
          static_cast<float>(std::sqrt(measured / (measured + static_cast<double>(nodes[child->second].point_count))));
    }
  }
  return scales;
}

std::array<std::uint32_t, 8> countOctants(std::span<const lod::PackedPoint> points, float half_cell) {
  std::array<std::uint32_t, 8> counts{};
  for (const lod::PackedPoint& p : points) {
    const unsigned octant = (p.x >= half_cell ? 1u : 0u) | (p.y >= half_cell ? 2u : 0u) | (p.z >= half_cell ? 4u : 0u);
    ++counts[octant];
  }
  return counts;
}

}  // namespace plumb::render
