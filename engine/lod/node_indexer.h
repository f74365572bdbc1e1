#pragma once
// Turns the points of one cell into that cell's subtree of octree nodes (paper section 3.1):
// an inner node keeps a thinned subsample of its points, about one point per occupied cell of a
// 128^3 grid over the node, and hands the rest to its children; a node with at most
// leaf_max_points points (or too small to split) is a leaf and keeps them all. The points of
// levels 0..L together hold about one point per occupied grid cell of level L: a near-uniform
// spacing of cube size / 128 / 2^L. Every input point is kept exactly once.
//
// The thinning keeps every point of a neighbourhood equally likely, wherever in its grid cell it
// lies. One point per grid cell would not: where a noisy wall's band of points straddles a grid
// plane, the few points beyond it get a cell, and a point, of their own, and every plane fitted to
// a coarse level moves towards the grid plane by a good part of the noise (docs/octree-format.md).

#include <cstdint>
#include <functional>
#include <span>
#include <unordered_set>
#include <vector>

#include "engine/lod/cube.h"

namespace plumb::lod {

using Position = std::array<double, 3>;

// The pseudo-random number the thinning ranks a point by: from the bits of its position, so the
// same point ranks the same whatever the order of the input or the chunking of the build.
std::uint64_t thinningHash(const Position& p);

// A point's place in the cube while the octree is built: per axis, its offset from the cube's
// minimum corner in 2^-32 of the cube's side. Its cell of level L <= 32 is its place shifted
// right by 32 - L (cellOf), exactly the cell Cube::cellAt gives for the position it was made from
// (both take the one product (p - origin) * (1 / size), the one scaled by 2^L, the other by 2^32).
// Half the bytes of three doubles, and cells by shifts instead of floors; the positions written
// come back within half a step (0.12 micrometres in a cube of a kilometre), far below any
// scanner's noise.
using GridPlace = std::array<std::uint32_t, 3>;
GridPlace placeOf(const Cube& cube, const Position& p);
// The coordinate of the cell of `level` (any level; beyond 32 the place's steps are the finest).
inline std::uint64_t cellOf(std::uint32_t place, std::uint32_t level) {
  return level <= 32 ? std::uint64_t{place} >> (32 - level) : std::uint64_t{place} << (level - 32);
}

// The octant of `key`'s child that holds place p: the lowest bit of its cell at the child's
// level, per axis (Cube::cellAt's child).
inline int octantOf(const CellKey& key, const GridPlace& p) {
  const std::uint32_t level = key.level + 1;
  return static_cast<int>((cellOf(p[0], level) & 1) | ((cellOf(p[1], level) & 1) << 1) |
                          ((cellOf(p[2], level) & 1) << 2));
}

// A point while the octree is built: its place, attributes and the high half of its thinning
// hash, 28 bytes (the chunk files hold them as they are).
struct BuildPoint {
  GridPlace place;
  std::array<std::uint16_t, 3> rgb;
  std::uint16_t intensity;
  std::uint16_t scan;  // index into the octree's scans (0 when the cloud has a single scan)
  std::uint16_t unused = 0;
  // thinningHash(x, y, z) >> 32 of the position read, made where the point enters the build:
  // every level's thinning ranks by it (ties: by a hash of the place, then the input order).
  std::uint32_t hash_high = 0;
};
static_assert(sizeof(BuildPoint) == 28);

// Receives each finished node: its key, its own points and which children exist. Nodes arrive
// children first. May be called from several threads at once when several indexers run.
using NodeSink = std::function<void(const CellKey& key, std::span<const BuildPoint> points, std::uint8_t child_mask)>;

// The roots of already indexed subtrees, and every cell above them.
struct StopSet {
  explicit StopSet(const std::vector<CellKey>& roots);
  std::unordered_set<CellKey, CellKeyHash> stops;
  std::unordered_set<CellKey, CellKeyHash> ancestors;
};

class NodeIndexer {
 public:
  NodeIndexer(const Cube& cube, std::uint32_t leaf_max_points);

  // Builds the subtree of `key` from `points` (all inside the cell; reordered in place).
  // `coarser` are the points that levels above this cell keep inside it. Returns whether the
  // node exists (false only for no points at all).
  bool indexSubtree(const CellKey& key, std::span<BuildPoint> points, std::span<const GridPlace> coarser,
                    const NodeSink& sink);

  // Builds the nodes above already indexed subtrees (the stops): `points` are the points the
  // stops' roots hold. Each stop is handed back through `stop_sink` with the points the levels
  // above did not take (possibly none); it returns whether the stop's node exists. Nodes here
  // are never leaves, and exist (perhaps without points) whenever a stop lies below them.
  using StopSink = std::function<bool(const CellKey& stop, std::span<const BuildPoint> remaining)>;
  bool indexAbove(const CellKey& key, std::span<BuildPoint> points, std::span<const GridPlace> coarser,
                  const StopSet& stops, const StopSink& stop_sink, const NodeSink& sink);

 private:
  // Keeps this node's subsample at the front of `points` and builds each child from the rest with
  // `index_child` (which returns whether the child exists); returns the number of points kept
  // and the mask of the children that exist.
  using ChildIndexer =
      std::function<bool(const CellKey& child, std::span<BuildPoint> points, std::span<const GridPlace> coarser)>;
  std::pair<std::size_t, std::uint8_t> keepSubsampleAndIndexChildren(const CellKey& key, std::span<BuildPoint> points,
                                                                     std::span<const GridPlace> coarser,
                                                                     const ChildIndexer& index_child);
  // Moves the grid subsample of `points` to its front and returns its size; grid cells holding
  // a `coarser` point take none.
  std::size_t selectSubsample(const CellKey& key, std::span<BuildPoint> points, std::span<const GridPlace> coarser);
  // The coarser points of each child: `coarser` and the node's own selection, by octant.
  std::array<std::vector<GridPlace>, 8> coarserForChildren(const CellKey& key, std::span<const GridPlace> coarser,
                                                           std::span<const BuildPoint> selected) const;
  // Reorders points by child octant; returns the 9 range boundaries.
  std::array<std::size_t, 9> splitByOctant(const CellKey& key, std::span<BuildPoint> points);
  bool isLeaf(const CellKey& key, std::size_t count) const;

  Cube cube_;
  std::uint32_t leaf_max_points_;
  // Scratch for selectSubsample, reused across nodes.
  struct Slot {  // an occupied grid cell
    std::uint32_t cell = 0;
    std::uint32_t coarser = 0;  // points of coarser levels in it
    std::uint32_t own = 0;      // this node's points in it
    std::uint32_t quota = 0;    // how many of them it keeps
    std::uint32_t first = 0;    // where its points start in order_
  };
  std::vector<std::uint64_t> cell_keys_;     // per point: its grid cell << 32 | its index
  std::vector<std::uint64_t> coarser_keys_;  // per coarser point: its grid cell << 32
  std::vector<std::uint64_t> sort_scratch_;
  std::vector<Slot> slots_;           // in cell order
  std::vector<std::uint32_t> score_;  // per point: hash_high
  std::vector<std::uint32_t> order_;
  std::vector<std::uint8_t> selected_;
  std::vector<std::uint8_t> octants_;
};

}  // namespace plumb::lod
