#pragma once
// Where an Octree's points live: the backend behind Octree (octree.h). The Octree keeps the
// header and the node index in memory and answers every query from them; a storage only loads
// one node's points. Two exist: Plumb's own file (plumb_storage.h) and a COPC file
// (copc_storage.h), so that the queries, the node cache, the grower and the renderer read both
// the same way.

#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "engine/lod/octree_format.h"

namespace plumb::lod {

// The points of one node, positions relative to `origin` (the cell's minimum corner).
struct NodePoints {
  CellKey key;
  std::array<double, 3> origin;
  std::vector<PackedPoint> points;
  // The scan of each point (an index into OctreeHeader::scans) where the cloud has a scan index
  // (kHasScanIndex), else empty.
  std::vector<std::uint16_t> scans;

  std::size_t size() const { return points.size(); }
  std::array<double, 3> position(std::size_t i) const {
    return {origin[0] + points[i].x, origin[1] + points[i].y, origin[2] + points[i].z};
  }
  std::size_t bytes() const {
    return sizeof(NodePoints) + points.capacity() * sizeof(PackedPoint) + scans.capacity() * sizeof(std::uint16_t);
  }
};

class OctreeStorage {
 public:
  virtual ~OctreeStorage() = default;

  // Reads the points of `node`, one of the nodes the storage was opened with. Thread-safe.
  // Throws plumb::Error naming the file and the byte offset on a read failure or corrupt data.
  virtual NodePoints load(const NodeInfo& node) const = 0;

  // The file's format in words, for 'plumb info': "Plumb octree 1", "COPC 1.0, LAZ 1.4 point
  // format 7".
  virtual std::string format() const = 0;
};

// What opening a file gives the Octree: its header, its nodes (sorted by level, then z, y, x,
// each key once, with child masks) and the storage that loads them.
struct OpenedOctree {
  OctreeHeader header;
  std::vector<NodeInfo> nodes;
  std::unique_ptr<OctreeStorage> storage;
};

}  // namespace plumb::lod
