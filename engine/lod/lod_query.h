#pragma once
// The spatial queries reco/ asks of an octree. Each descends from the root through existing
// nodes only and stops where the region ends, so its cost follows the size of the region and the
// level asked for, never the size of the cloud (QueryStats counts the nodes it looked at).
// Thread-safe: they only read the octree's index.

#include <array>
#include <cstdint>
#include <memory>
#include <unordered_map>
#include <vector>

#include "engine/lod/octree.h"

namespace plumb::lod {

struct QueryStats {
  std::uint64_t nodes_visited = 0;
};

// Nodes of levels 0..max_level whose cell intersects the sphere: together they hold the points
// of the region at spacing octree.spacing(max_level) (or finer where the tree ends earlier).
// Ordered parents before children.
std::vector<const NodeInfo*> nodesInSphere(const Octree& octree, const std::array<double, 3>& centre, double radius,
                                           std::uint32_t max_level, QueryStats* stats = nullptr);

// Cells of exactly `level` that intersect the sphere and hold a node.
std::vector<CellKey> cellsInSphere(const Octree& octree, const std::array<double, 3>& centre, double radius,
                                   std::uint32_t level, QueryStats* stats = nullptr);

// The same cells ordered by the distance of their box from `point` (nearest first; ties by key).
std::vector<CellKey> cellsByDistance(const Octree& octree, const std::array<double, 3>& point, double radius,
                                     std::uint32_t level, QueryStats* stats = nullptr);

// Which of the 26 neighbours of `key` hold a node.
std::vector<CellKey> existingNeighbours(const Octree& octree, const CellKey& key);

class NodeCache;

// A point's identity in an octree: the node that stores it (its index in Octree::nodes()) and its
// index in that node. Every point is stored once, so a point has the same identity in the cells
// of every level that include it: what lets the region grower switch levels without counting a
// point twice.
struct PointRef {
  std::uint32_t node = 0;
  std::uint32_t index = 0;
  bool operator==(const PointRef&) const = default;
};

struct CellPoint {
  std::array<double, 3> position;  // world coordinates
  PointRef ref;
};

// The points of octree cells at their level's spacing, for a caller that asks for many cells (a
// grow visits tens of thousands at full detail). The points of cell `key` are those of its own
// node and those of its ancestors that lie in the cell (Cube::cellAt decides, so each point of
// levels 0..key.level belongs to exactly one cell of key.level). An ancestor holds the points of
// thousands of cells of a deep level: scanning all of them for every cell made a cell's cost
// follow the depth and the nodes' sizes, not what it returns. Instead each ancestor's points are
// grouped once per level asked by the cell they fall in (a BucketIndex), and a cell's points
// are a table look-up away. Not thread-safe: one per user (a grow). Keeps the nodes it has
// grouped alive while it lives.
class CellPointIndex {
 public:
  explicit CellPointIndex(NodeCache& cache);
  ~CellPointIndex();
  CellPointIndex(const CellPointIndex&) = delete;
  CellPointIndex& operator=(const CellPointIndex&) = delete;

  // The points of `key`, its own node's first, then each ancestor's from the nearest up, each in
  // storage order. Cost: the points returned plus a look-up per ancestor; the first query of a
  // level that meets an ancestor groups that ancestor's points, O(n) for its n points. Loads
  // through the cache; blocks on nodes not yet loaded.
  std::vector<CellPoint> pointsInCell(const CellKey& key);

  // The points of levels 0..point_level (>= key.level) inside cell `key`: those of
  // pointsInCell(key), then those of its descendant nodes down to point_level, parents before
  // children. What the cells of point_level inside `key` hold together, for a caller that
  // works in coarser cells than the density it wants (a grow at full detail).
  std::vector<CellPoint> pointsInCell(const CellKey& key, std::uint32_t point_level);

 private:
  struct SortedNode;
  const SortedNode& sorted(const NodeInfo& node, std::uint32_t level);

  NodeCache& cache_;
  std::unordered_map<std::uint64_t, std::unique_ptr<SortedNode>> sorted_;  // by node index and level
};

}  // namespace plumb::lod
