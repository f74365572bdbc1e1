#pragma once
// A built octree opened for reading: its header and node index in memory, node points loaded on
// demand (directly with load(), or through NodeCache). Opening checks the header and the index;
// loading a node checks its checksum. Immutable after open: every const member is thread-safe.

#include <array>
#include <memory>
#include <string>
#include <unordered_map>
#include <vector>

#include "engine/lod/octree_format.h"

namespace plumb::lod {

// The points of one node, positions relative to `origin` (the cell's minimum corner).
struct NodePoints {
  CellKey key;
  std::array<double, 3> origin;
  std::vector<PackedPoint> points;

  std::size_t size() const { return points.size(); }
  std::array<double, 3> position(std::size_t i) const {
    return {origin[0] + points[i].x, origin[1] + points[i].y, origin[2] + points[i].z};
  }
  std::size_t bytes() const { return sizeof(NodePoints) + points.capacity() * sizeof(PackedPoint); }
};

class Octree {
 public:
  // Opens and validates `path`. Throws plumb::Error naming the file and the byte offset for a
  // file that is not an octree, is newer than this Plumb, truncated or corrupt.
  static std::shared_ptr<const Octree> open(const std::string& path);
  // Whether `path` starts with the octree's magic (an octree, or a damaged one open() names);
  // false for a point file or an unreadable path.
  static bool looksLikeOctree(const std::string& path);
  ~Octree();
  Octree(const Octree&) = delete;
  Octree& operator=(const Octree&) = delete;

  const std::string& path() const { return path_; }
  const OctreeHeader& header() const { return header_; }
  const Cube& cube() const { return header_.cube; }

  // All nodes, sorted by level, then z, y, x.
  const std::vector<NodeInfo>& nodes() const { return nodes_; }
  // The node of `key`, or null when that cell holds no node.
  const NodeInfo* find(const CellKey& key) const;

  // Spacing of the points that levels 0..level give together, in metres.
  double spacing(std::uint32_t level) const;
  // The shallowest level whose spacing is at most `spacing` (clamped to the octree's depth).
  std::uint32_t levelForSpacing(double spacing) const;

  // Reads and verifies one node's points. Thread-safe (pread). Throws plumb::Error on a
  // checksum mismatch or a read failure.
  NodePoints load(const NodeInfo& node) const;

 private:
  Octree() = default;

  std::string path_;
  int fd_ = -1;
  OctreeHeader header_;
  std::vector<NodeInfo> nodes_;
  std::unordered_map<CellKey, std::size_t, CellKeyHash> lookup_;
};

}  // namespace plumb::lod
