// libFuzzer target for Plumb's octree file (engine/lod, docs/octree-format.md): Octree::open,
// then every node found by its key and loaded. Any input must end in an open octree whose nodes
// load, or in a plumb::Error, never in a crash, a hang or a sanitizer report. Run by
// scripts/fuzz, and replayed in the test suite (fuzz_replay_main.cpp).
//
// The header, the node index and every node block carry a CRC-32, so almost every mutation would
// stop at the first checksum. The harness repairs the checksums before opening (what a file
// written by a buggy writer would hold), so mutations reach the structure checks behind them;
// octree_test.cpp checks that a wrong checksum is reported.

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <span>
#include <vector>

#include "engine/core/error.h"
#include "engine/lod/octree.h"
#include "tests/fuzz/memory_file.h"

namespace {

using plumb::lod::kHeaderBytes;
using plumb::lod::kIndexEntryBytes;

// `bytes` with the checksums of whatever lies inside the file recomputed: node blocks (through the
// index entries), the index, the scan table, then the header. Unchanged when the header is not one of this
// version: then there is nothing to repair, and open() must say what is wrong.
void repairChecksums(std::vector<std::byte>& bytes) {
  if (bytes.size() < kHeaderBytes) return;
  const auto header_bytes = std::span(bytes).first<kHeaderBytes>();
  // The header's checksum is its last 4 bytes: make it right first, so that decodeHeader
  // checks the rest.
  const std::uint32_t header_crc = plumb::lod::crc32Of(header_bytes.first(kHeaderBytes - 4));
  std::memcpy(bytes.data() + kHeaderBytes - 4, &header_crc, 4);
  plumb::lod::OctreeHeader header;
  try {
    header = plumb::lod::decodeHeader(header_bytes, "fuzz input");
  } catch (const plumb::Error&) {
    return;
  }
  const std::uint64_t size = bytes.size();
  if (header.index_offset > size || header.index_bytes > size - header.index_offset) return;
  const auto index = std::span(bytes).subspan(header.index_offset, header.index_bytes);
  for (std::size_t at = 0; at + kIndexEntryBytes <= index.size(); at += kIndexEntryBytes) {
    plumb::lod::NodeInfo node = plumb::lod::decodeIndexEntry(index.data() + at, header.attributes);
    const std::uint64_t block = node.bytes;
    if (node.offset > size || block > size - node.offset) continue;
    node.crc = plumb::lod::crc32Of(std::span(bytes).subspan(node.offset, block));
    plumb::lod::encodeIndexEntry(node, index.data() + at);
  }
  header.index_crc = plumb::lod::crc32Of(index);
  if (header.scan_table_offset <= size && header.scan_table_bytes <= size - header.scan_table_offset) {
    header.scan_table_crc =
        plumb::lod::crc32Of(std::span(bytes).subspan(header.scan_table_offset, header.scan_table_bytes));
  }
  const auto repaired = plumb::lod::encodeHeader(header);
  std::memcpy(bytes.data(), repaired.data(), kHeaderBytes);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::vector<std::byte> bytes(size);
  if (size > 0) std::memcpy(bytes.data(), data, size);
  repairChecksums(bytes);
  try {
    const auto tree = plumb::lod::Octree::open(
        plumb::fuzz::memoryFile(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size()));
    (void)tree->levelForSpacing(tree->header().root_spacing / 1000.0);
    for (const auto& node : tree->nodes()) {
      // Every listed node must be found by its key (a repeated key finds one of its entries).
      if (tree->find(node.key) == nullptr) __builtin_trap();
      const plumb::lod::NodePoints points = tree->load(node);
      if (points.size() != node.point_count) __builtin_trap();
      for (std::size_t i = 0; i < points.size(); ++i) (void)points.position(i);
    }
  } catch (const plumb::Error&) {
    // Malformed input, reported: what open() and load() must do.
  }
  return 0;
}
