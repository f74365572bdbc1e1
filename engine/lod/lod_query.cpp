#include "engine/lod/lod_query.h"

#include <algorithm>

#include "engine/core/bucket_index.h"
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

namespace {

// Appends every point of `node` (loaded through `cache`) to `result`, in storage order.
void appendNodePoints(NodeCache& cache, const NodeInfo& node, std::vector<CellPoint>& result) {
  const auto points = cache.get(node.key);
  const auto node_index = static_cast<std::uint32_t>(&node - cache.octree().nodes().data());
  // Geometrically: a cell that gathers many descendant nodes grew its vector by one node at a
  // time when this reserved the exact size, copying it whole for every node.
  const std::size_t needed = result.size() + points->size();
  if (needed > result.capacity()) result.reserve(std::max(needed, 2 * result.capacity()));
  for (std::size_t i = 0; i < points->size(); ++i) {
    result.push_back({points->position(i), {node_index, static_cast<std::uint32_t>(i)}});
  }
}

}  // namespace

// An ancestor's points grouped by their cell at one deeper level.
struct CellPointIndex::SortedNode {
  std::shared_ptr<const NodePoints> points;
  std::uint32_t node_index = 0;
  BucketIndex<CellKey, CellKeyHash> cells;  // item i: point i
};

CellPointIndex::CellPointIndex(NodeCache& cache) : cache_(cache) {}
CellPointIndex::~CellPointIndex() = default;

const CellPointIndex::SortedNode& CellPointIndex::sorted(const NodeInfo& node, std::uint32_t level) {
  const Octree& octree = cache_.octree();
  const auto node_index = static_cast<std::uint32_t>(&node - octree.nodes().data());
  auto& slot = sorted_[(std::uint64_t{node_index} << 6) | level];
  if (slot) return *slot;
  slot = std::make_unique<SortedNode>();
  slot->points = cache_.get(node.key);
  slot->node_index = node_index;
  const NodePoints& points = *slot->points;
  std::vector<CellKey> cells(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) cells[i] = octree.cube().cellAt(points.position(i), level);
  slot->cells = BucketIndex<CellKey, CellKeyHash>(cells);
  return *slot;
}

std::vector<CellPoint> CellPointIndex::pointsInCell(const CellKey& key) {
  std::vector<CellPoint> result;
  const Octree& octree = cache_.octree();
  if (const NodeInfo* own = octree.find(key)) appendNodePoints(cache_, *own, result);
  for (std::optional<CellKey> level = key.parent(); level; level = level->parent()) {
    const NodeInfo* node = octree.find(*level);
    if (node == nullptr) continue;
    const SortedNode& ancestor = sorted(*node, key.level);
    for (const std::uint32_t i : ancestor.cells.at(key)) {
      result.push_back({ancestor.points->position(i), {ancestor.node_index, i}});
    }
  }
  return result;
}

std::vector<CellPoint> CellPointIndex::pointsInCell(const CellKey& key, std::uint32_t point_level) {
  std::vector<CellPoint> result = pointsInCell(key);
  const Octree& octree = cache_.octree();
  const NodeInfo* own = octree.find(key);
  if (own == nullptr || point_level <= key.level) return result;
  // Breadth-first through the existing descendants: every point of theirs lies inside `key`.
  std::vector<const NodeInfo*> level_nodes{own};
  for (std::uint32_t level = key.level; level < point_level && !level_nodes.empty(); ++level) {
    std::vector<const NodeInfo*> next;
    for (const NodeInfo* node : level_nodes) {
      for (int octant = 0; octant < 8; ++octant) {
        if (!((node->child_mask >> octant) & 1u)) continue;
        const NodeInfo* child = octree.find(node->key.child(octant));
        if (child == nullptr) continue;
        next.push_back(child);
        appendNodePoints(cache_, *child, result);
      }
    }
    level_nodes = std::move(next);
  }
  return result;
}

}  // namespace plumb::lod
