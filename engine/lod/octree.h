#pragma once
// An octree opened for reading: its header and node index in memory, node points loaded on
// demand (directly with load(), or through NodeCache) from its storage (octree_storage.h): a
// Plumb octree built by 'plumb import', or a COPC file read in place. Opening checks the header
// and the index; loading a node checks its data. Immutable after open: every const member is
// thread-safe.

#include <array>
#include <memory>
#include <string>
#include <unordered_map>
#include <vector>

#include "engine/lod/octree_format.h"
#include "engine/lod/octree_storage.h"

namespace plumb::lod {

class Octree {
 public:
  // Opens and validates `path`, a Plumb octree or a COPC file (plumb_storage.h,
  // copc_storage.h). Throws plumb::Error naming the file and the byte offset for a file that is
  // neither, is newer than this Plumb, truncated or corrupt.
  static std::shared_ptr<const Octree> open(const std::string& path);
  // Whether `path` starts as an octree does: the Plumb octree's magic, or a LAS header followed
  // by the COPC info VLR (an octree, or a damaged one open() names); false for a point file
  // (LAS or LAZ without COPC included) or an unreadable path.
  static bool looksLikeOctree(const std::string& path);
  ~Octree();
  Octree(const Octree&) = delete;
  Octree& operator=(const Octree&) = delete;

  const std::string& path() const { return path_; }
  const OctreeHeader& header() const { return header_; }
  const Cube& cube() const { return header_.cube; }
  // The file's format in words: "Plumb octree 1", "COPC 1.0, LAZ 1.4 point format 7".
  std::string format() const { return storage_->format(); }

  // All nodes, sorted by level, then z, y, x.
  const std::vector<NodeInfo>& nodes() const { return nodes_; }
  // The node of `key`, or null when that cell holds no node.
  const NodeInfo* find(const CellKey& key) const;

  // Spacing of the points that levels 0..level give together, in metres.
  double spacing(std::uint32_t level) const;
  // The shallowest level whose spacing is at most `spacing` (clamped to the octree's depth).
  std::uint32_t levelForSpacing(double spacing) const;

  // Reads and verifies one node's points (one of nodes()). Thread-safe. Throws plumb::Error on a
  // checksum mismatch, corrupt compressed data or a read failure.
  NodePoints load(const NodeInfo& node) const { return storage_->load(node); }

 private:
  Octree() = default;

  std::string path_;
  std::unique_ptr<OctreeStorage> storage_;
  OctreeHeader header_;
  std::vector<NodeInfo> nodes_;
  std::unordered_map<CellKey, std::size_t, CellKeyHash> lookup_;
};

}  // namespace plumb::lod
