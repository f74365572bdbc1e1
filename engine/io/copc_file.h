#pragma once
// A COPC file (Cloud Optimized Point Cloud Specification 1.0, Hobu Inc. 2021, copc.io) opened for
// random access: a LAZ 1.4 file (point formats 6 to 8, layered compressor, variable chunks) whose
// info VLR places an octree over the points and whose hierarchy lists the LAZ chunk of every
// octree node. Reading the whole file in order is openLas's job (COPC is valid LAZ); this reads the
// octree: its hierarchy once at open, then any node's chunk on its own.

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "engine/io/las_header.h"
#include "engine/io/point_reader.h"

namespace plumb::io {

// The info VLR (specification section "info VLR"; user id "copc", record id 1, 160 bytes).
struct CopcInfo {
  std::array<double, 3> center{};  // of the octree's root cube, in world coordinates
  double halfsize = 0.0;           // from the center to each face of the root cube
  double spacing = 0.0;            // between the points of the root node; halved at each level
  std::uint64_t root_hier_offset = 0;
  std::uint64_t root_hier_size = 0;
  double gpstime_minimum = 0.0, gpstime_maximum = 0.0;
};

// One node of the hierarchy (section "hierarchy VLR": an Entry of a hierarchy page).
struct CopcNode {
  std::int32_t level = 0;  // the VoxelKey (d, x, y, z): level d, x y z in [0, 2^d)
  std::int32_t x = 0, y = 0, z = 0;
  std::uint64_t offset = 0;        // file offset of the node's LAZ chunk (0 points: none)
  std::uint32_t bytes = 0;         // of the chunk
  std::uint32_t points = 0;        // 0: a node the hierarchy names but that holds no points
  std::uint64_t entry_offset = 0;  // file offset of the hierarchy entry, for errors
};

class CopcFile {
 public:
  // Whether `path` looks like COPC: a LAS file whose first VLR (at the end of the header, as the
  // specification requires) is the COPC info VLR. Reads a few hundred bytes; false for any
  // other file or an unreadable path. A damaged COPC file answers true, so that open() names
  // the damage.
  static bool looksLikeCopc(const std::string& path);

  // Reads the LAS header, the info VLR and every hierarchy page (following child pages).
  // Throws plumb::Error naming the file, the byte offset and the fault for anything a reader of
  // the octree cannot trust: not LAS, no info VLR, a point format other than 6 to 8 or points
  // not compressed in layered chunks, a halfsize or spacing that is not positive and finite, a
  // hierarchy page outside the file or not a whole number of entries, a page visited twice, an
  // entry whose key lies outside the cube (x, y or z not in [0, 2^d), d beyond 30) or repeats,
  // a point count below -1 or above the file's or 2^24, a chunk outside the point data or shorter than
  // one record, or node point counts whose sum is not the header's.
  explicit CopcFile(std::string path);

  const std::string& path() const { return path_; }
  const LasHeader& header() const { return header_; }
  const CopcInfo& info() const { return info_; }
  // Every entry that holds points or names an empty node, in the order the pages list them.
  const std::vector<CopcNode>& nodes() const { return nodes_; }

  // Decodes the chunk of `node` (one of nodes(), with points) into `points`, replacing them:
  // position (X * scale + offset), intensity, colour (formats 7 and 8). Thread-safe: each call
  // reads through its own file handle. Throws plumb::Error naming the file, the chunk and the
  // byte offset for a truncated or corrupt chunk.
  void readNode(const CopcNode& node, std::vector<PointRecord>& points) const;

  // "COPC 1.0, LAZ 1.4 point format 7"
  std::string format() const;

 private:
  void readInfo(FileSource& source);
  void readHierarchy(FileSource& source);

  std::string path_;
  LasHeader header_;
  CopcInfo info_;
  std::uint64_t info_offset_ = 0;  // of the info VLR's payload
  std::vector<CopcNode> nodes_;
};

}  // namespace plumb::io
