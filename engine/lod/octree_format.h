#pragma once
// The on-disk layout of a Plumb octree (.plumb), version 1. docs/octree-format.md is the
// reference; this header is its single implementation. All integers and floats little-endian.
//
//   [header: 256 bytes] [node blocks ...] [node index: node_count * 40 bytes]
//
// Every node block, the index and the header carry a CRC-32 (zlib's polynomial), so that any
// corruption is reported as such instead of producing wrong points.

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>

#include "engine/lod/cell_key.h"
#include "engine/lod/cube.h"

namespace plumb::lod {

constexpr std::array<char, 8> kOctreeMagic{'P', 'L', 'U', 'M', 'B', 'O', 'C', 'T'};
constexpr std::uint32_t kOctreeVersion = 1;
constexpr std::size_t kHeaderBytes = 256;
constexpr std::size_t kIndexEntryBytes = 40;
constexpr std::size_t kPointBytes = 20;
// Inner cells keep about one point per occupied cell of a kSamplingGrid^3 grid: their spacing
// is size / 128 (docs/octree-format.md).
constexpr std::uint32_t kSamplingGrid = 128;

enum AttributeFlags : std::uint32_t { kHasColour = 1, kHasIntensity = 2 };

struct OctreeHeader {
  std::uint64_t point_count = 0;
  std::uint64_t node_count = 0;
  Cube cube;
  double root_spacing = 0.0;  // spacing of level 0; level L has root_spacing / 2^L
  std::uint32_t sampling_grid = kSamplingGrid;
  std::uint32_t depth = 0;  // deepest level with a node
  std::uint32_t attributes = 0;
  std::uint32_t leaf_max_points = 0;
  Box3 bounds{};                         // of the points
  std::uint64_t skipped_non_finite = 0;  // input points without a valid position (io::ReadCounts::non_finite)
  std::uint64_t index_offset = 0;
  std::uint64_t index_bytes = 0;
  std::uint32_t index_crc = 0;
  std::uint32_t input_files = 0;
};

struct NodeInfo {
  CellKey key;
  std::uint32_t point_count = 0;
  std::uint32_t crc = 0;        // of the node block (Plumb's file; 0 in a COPC file, whose chunks have none)
  std::uint64_t offset = 0;     // of the node block in the file (COPC: of the node's LAZ chunk)
  std::uint8_t child_mask = 0;  // bit i: child octant i exists
  std::uint64_t bytes = 0;      // of the node block, what loading it reads (Plumb: implied, not in the index)
};

// One stored point: position relative to its cell's minimum corner, colour and intensity.
struct PackedPoint {
  float x, y, z;
  std::array<std::uint16_t, 3> rgb;
  std::uint16_t intensity;
};

std::uint32_t crc32Of(std::span<const std::byte> bytes);

std::array<std::byte, kHeaderBytes> encodeHeader(const OctreeHeader& header);
// Throws plumb::Error naming `path` for a wrong magic, version, size or checksum.
OctreeHeader decodeHeader(std::span<const std::byte, kHeaderBytes> bytes, const std::string& path);

void encodeIndexEntry(const NodeInfo& node, std::byte* out);
NodeInfo decodeIndexEntry(const std::byte* in);

void encodePoint(const PackedPoint& point, std::byte* out);
PackedPoint decodePoint(const std::byte* in);

}  // namespace plumb::lod
