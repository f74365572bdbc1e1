#include "engine/lod/lod_query.h"

#include <algorithm>

#include "engine/lod/node_cache.h"

namespace plumb::lod {
namespace {

// Depth-first descent through existing children whose cells meet the sphere.
template <typename Visit>
void descend(const Octree& octree, const std::array<double, 3>& centre, double radius, std::uint32_t max_level,
             QueryStats* stats, Visit&& visit) {
  const NodeInfo* root = octree.find(CellKey{});
  if (root == nullptr) return;
  const double radius2 = radius * radius;
  std::vector<const NodeInfo*> stack{root};
  while (!stack.empty()) {
    const NodeInfo* node = stack.back();
    stack.pop_back();
    if (stats) ++stats->nodes_visited;
    if (octree.cube().squaredDistance(node->key, centre) > radius2) continue;
    visit(*node);
    if (node->key.level >= max_level) continue;
    for (int octant = 7; octant >= 0; --octant) {
      if ((node->child_mask >> octant) & 1u) {
        if (const NodeInfo* child = octree.find(node->key.child(octant))) stack.push_back(child);
      }
    }
  }
}

}  // namespace

std::vector<const NodeInfo*> nodesInSphere(const Octree& octree, const std::array<double, 3>& centre, double radius,
                                           std::uint32_t max_level, QueryStats* stats) {
  std::vector<const NodeInfo*> result;
  descend(octree, centre, radius, max_level, stats, [&](const NodeInfo& node) { result.push_back(&node); });
  std::stable_sort(result.begin(), result.end(),
                   [](const NodeInfo* a, const NodeInfo* b) { return a->key.level < b->key.level; });
  return result;
}

std::vector<CellKey> cellsInSphere(const Octree& octree, const std::array<double, 3>& centre, double radius,
                                   std::uint32_t level, QueryStats* stats) {
  std::vector<CellKey> result;
  descend(octree, centre, radius, level, stats, [&](const NodeInfo& node) {
    if (node.key.level == level) result.push_back(node.key);
  });
  return result;
}

std::vector<CellKey> cellsByDistance(const Octree& octree, const std::array<double, 3>& point, double radius,
                                     std::uint32_t level, QueryStats* stats) {
  std::vector<CellKey> cells = cellsInSphere(octree, point, radius, level, stats);
  std::vector<std::pair<double, CellKey>> keyed;
  keyed.reserve(cells.size());
  for (const CellKey& key : cells) keyed.emplace_back(octree.cube().squaredDistance(key, point), key);
  std::sort(keyed.begin(), keyed.end());
  for (std::size_t i = 0; i < keyed.size(); ++i) cells[i] = keyed[i].second;
  return cells;
}

std::vector<CellKey> existingNeighbours(const Octree& octree, const CellKey& key) {
  std::vector<CellKey> result;
  for (const CellKey& neighbour : key.neighbours()) {
    if (octree.find(neighbour) != nullptr) result.push_back(neighbour);
  }
  return result;
}

std::vector<CellPoint> pointsInCell(NodeCache& cache, const CellKey& key) {
  std::vector<CellPoint> result;
  const Octree& octree = cache.octree();
  const Cube& cube = octree.cube();
  for (std::optional<CellKey> level = key; level; level = level->parent()) {
    const NodeInfo* node = octree.find(*level);
    if (node == nullptr) continue;
    const auto points = cache.get(*level);
    const auto node_index = static_cast<std::uint32_t>(node - octree.nodes().data());
    for (std::size_t i = 0; i < points->size(); ++i) {
      const std::array<double, 3> p = points->position(i);
      if (level->level == key.level || cube.cellAt(p, key.level) == key) {
        result.push_back({p, {node_index, static_cast<std::uint32_t>(i)}});
      }
    }
  }
  return result;
}

}  // namespace plumb::lod
