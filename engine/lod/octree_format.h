#pragma once
// The on-disk layout of a Plumb octree (.plumb), version 3. docs/octree-format.md is the
// reference; this header is its single implementation. All integers and floats little-endian.
//
//   [header: 256 bytes] [node blocks ...] [node index: node_count * 40 bytes] [scan table]
//
// Every node block, the index, the scan table and the header carry a CRC-32 (zlib's
// polynomial), so that any corruption is reported as such instead of producing wrong points.
// Version 1 files (no scans) are read as they are: their layout is version 2's without the
// scan index; version 2's is version 3's without the framing box.

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "engine/lod/cell_key.h"
#include "engine/lod/cube.h"

namespace plumb::lod {

constexpr std::array<char, 8> kOctreeMagic{'P', 'L', 'U', 'M', 'B', 'O', 'C', 'T'};
constexpr std::uint32_t kOctreeVersion = 3;
constexpr std::uint32_t kOldestOctreeVersion = 1;
constexpr std::size_t kHeaderBytes = 256;
constexpr std::size_t kIndexEntryBytes = 40;
constexpr std::size_t kPointBytes = 20;
constexpr std::size_t kScanIndexBytes = 2;  // per point, after a node's points, with kHasScanIndex
// Inner cells keep about one point per occupied cell of a kSamplingGrid^3 grid: their spacing
// is size / 128 (docs/octree-format.md).
constexpr std::uint32_t kSamplingGrid = 128;

// kHasScanIndex: the cloud merges several scans (E57 data3D, or several input files) and every
// point keeps the index of its scan (OctreeHeader::scans names them).
enum AttributeFlags : std::uint32_t { kHasColour = 1, kHasIntensity = 2, kHasScanIndex = 4 };

// Bytes a node of `point_count` points takes in a file with `attributes`.
constexpr std::uint64_t nodeBlockBytes(std::uint64_t point_count, std::uint32_t attributes) {
  return point_count * (kPointBytes + ((attributes & kHasScanIndex) != 0 ? kScanIndexBytes : 0));
}

struct OctreeHeader {
  std::uint32_t version = kOctreeVersion;  // as read; written as kOctreeVersion
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
  // Version 2: where the scan table lies (0 bytes: none). The names themselves are in `scans`
  // once the table is read (openPlumbOctree), not in the 256 header bytes.
  std::uint64_t scan_table_offset = 0;
  std::uint64_t scan_table_bytes = 0;
  std::uint32_t scan_table_crc = 0;
  std::uint32_t scan_count = 0;
  // The scans the cloud merges, in index order: "<file>" for a single-scan file, "<file>:
  // <name>" for a scan of an E57 file. Empty when the cloud has no scan index.
  std::vector<std::string> scans;
  // Version 3: the box that frames the cloud's bulk, inside `bounds` (framing.h; measured on
  // every point by the import). Absent in older files and COPC files: framingBox() samples them.
  std::optional<Box3> framing;
};

struct NodeInfo {
  CellKey key;
  std::uint32_t point_count = 0;
  std::uint32_t crc = 0;        // of the node block (Plumb's file; 0 in a COPC file, whose chunks have none)
  std::uint64_t offset = 0;     // of the node block in the file (COPC: of the node's LAZ chunk)
  std::uint8_t child_mask = 0;  // bit i: child octant i exists
  std::uint64_t bytes = 0;      // of the node block, what loading it reads (Plumb: implied, not in the index)
};

// The scan table (version 2): scan_count names, each a u32 byte length and UTF-8 bytes.
std::vector<std::byte> encodeScanTable(const std::vector<std::string>& names);
// Throws plumb::Error naming `path` and the byte offset (from `offset`, the table's place) for a
// table that is not `count` names filling its bytes exactly.
std::vector<std::string> decodeScanTable(std::span<const std::byte> bytes, std::uint32_t count, const std::string& path,
                                         std::uint64_t offset);

// One stored point: position relative to its cell's minimum corner, colour and intensity. (Its
// scan index, where the cloud has one, is stored after the node's points: NodePoints::scans.)
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
// `attributes` (the header's) give the node block's size.
NodeInfo decodeIndexEntry(const std::byte* in, std::uint32_t attributes);

void encodePoint(const PackedPoint& point, std::byte* out);
PackedPoint decodePoint(const std::byte* in);

}  // namespace plumb::lod
