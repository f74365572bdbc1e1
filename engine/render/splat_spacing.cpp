#include "engine/render/splat_spacing.h"

#include <cmath>
#include <unordered_map>

namespace plumb::render {
namespace {

// The share of the drawn points that are the node's own, as sqrt: the node has `own` points in a
// region where its ancestors have `above` (the parent's there, plus a third for those higher up).
double densityScale(double own, double above) {
  return own > 0.0 ? std::sqrt(own / (own + 4.0 / 3.0 * above)) : 1.0;
}

}  // namespace

std::vector<std::array<float, 8>> octantRadiusScales(std::span<const DrawnNode> nodes) {
  std::unordered_map<lod::CellKey, std::size_t, lod::CellKeyHash> index;
  index.reserve(nodes.size());
  for (std::size_t i = 0; i < nodes.size(); ++i) index.emplace(nodes[i].key, i);

  std::vector<std::array<float, 8>> scales(nodes.size());
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    const DrawnNode& node = nodes[i];
    // Where the node is the finest drawn: its points among its ancestors'.
    double own_scale = 1.0;
    if (node.key.level > 0) {
      const auto parent = index.find(*node.key.parent());
      if (parent != index.end()) {
        own_scale = densityScale(node.point_count,
                                 nodes[parent->second].octant_points[static_cast<std::size_t>(node.key.octant())]);
      }
    }
    for (int octant = 0; octant < 8; ++octant) {
      const auto o = static_cast<std::size_t>(octant);
      const auto child = index.find(node.key.child(octant));
      // Where a child is drawn, the node's points lie among the child's, whose region the
      // node's points there stand for: a child's points count as a parent's do against them.
      const double scale =
          child == index.end() || node.octant_points[o] == 0
              ? own_scale
              : std::sqrt(node.octant_points[o] /
                          (4.0 / 3.0 * node.octant_points[o] + static_cast<double>(nodes[child->second].point_count)));
      scales[i][o] = static_cast<float>(scale);
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
