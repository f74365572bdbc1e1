// COPC, random access (Cloud Optimized Point Cloud Specification 1.0, Hobu Inc. 2021,
// https://copc.io; sections "LAS PDRFs 6, 7, or 8", "info VLR", "hierarchy VLR" and "Reader
// Implementation Notes"). Read from the specification, no code copied.
//
//   1. The LAS 1.4 header and the laszip VLR (las_header.h). COPC requires point formats 6 to 8
//      in LAZ's layered chunked coding with variable chunks.
//   2. The info VLR, the first VLR of the file (user id "copc", record id 1), 160 bytes, all
//      little-endian: center x y z (f64), halfsize (f64), spacing (f64), root_hier_offset
//      (u64), root_hier_size (u64), gpstime minimum and maximum (f64), 11 reserved u64.
//   3. The hierarchy (the "copc" record 1000 VLR or EVLR; the info VLR locates its root page, so
//      its own header is not needed): pages of 32-byte entries, VoxelKey (d, x, y, z: i32 each),
//      offset (u64), byteSize (i32), pointCount (i32). pointCount -1: a child page of byteSize
//      bytes at offset; 0: a node without points; n > 0: the node's n points are one LAZ chunk
//      of byteSize bytes at offset, decodable on its own (its first point raw, then its layers).
//   4. A node's points lie in the cube of its key: side 2 halfsize / 2^d, from
//      center - halfsize + (x, y, z) * side. Level d's points together have spacing
//      spacing / 2^d.

#include "engine/io/copc_file.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <optional>
#include <set>
#include <string_view>
#include <unordered_set>
#include <utility>

#include "engine/io/byte_order.h"
#include "engine/io/file_source.h"
#include "engine/io/laz_chunk_table.h"
#include "engine/io/laz_point_decompressor.h"

namespace plumb::io {
namespace {

constexpr std::string_view kCopcUserId = "copc";
constexpr std::uint16_t kCopcInfoRecordId = 1;
constexpr std::size_t kInfoBytes = 160;
constexpr std::size_t kEntryBytes = 32;
// Deeper keys than this cannot be addressed with 32-bit cell coordinates; 2^30 cells per axis
// already keep a 1000 km cube at 1 mm.
constexpr std::int32_t kMaxLevel = 30;
// A node is a unit of streaming: writers keep them near 10^5 points. A count beyond this one is
// corruption, refused before decoding it would allocate gigabytes.
constexpr std::uint32_t kMaxNodePoints = std::uint32_t{1} << 24;
// A COPC file's point data starts with the 8-byte offset of LAZ's chunk table.
constexpr std::uint64_t kChunkTableOffsetBytes = 8;

// Where looksLikeCopc looks: the header size field, and the user and record ids of a VLR header;
// and the point format byte, for errors.
constexpr std::size_t kHeaderSizeAt = 94;
constexpr std::size_t kPointFormatAt = 104;
constexpr std::size_t kVlrUserIdAt = 2;
constexpr std::size_t kVlrRecordIdAt = 18;
constexpr std::size_t kVlrHeaderBytes = 54;

std::string keyText(std::int32_t d, std::int32_t x, std::int32_t y, std::int32_t z) {
  // Appended piece by piece: GCC 12 warns falsely (-Wrestrict) on "(" + std::to_string(d) + ...
  std::string text = "(";
  for (const std::int32_t v : {d, x, y, z}) {
    if (text.size() > 1) text += ", ";
    text += std::to_string(v);
  }
  return text + ")";
}

}  // namespace

bool CopcFile::looksLikeCopc(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::array<char, 96> start{};
  in.read(start.data(), start.size());
  if (in.gcount() != static_cast<std::streamsize>(start.size()) || std::memcmp(start.data(), "LASF", 4) != 0) {
    return false;
  }
  const auto header_size =
      loadLittleEndian<std::uint16_t>(reinterpret_cast<const std::byte*>(start.data()) + kHeaderSizeAt);
  std::array<char, kVlrHeaderBytes> vlr{};
  in.seekg(header_size);
  in.read(vlr.data(), vlr.size());
  if (in.gcount() != static_cast<std::streamsize>(vlr.size())) return false;
  std::string_view user(vlr.data() + kVlrUserIdAt, 16);
  user = user.substr(0, user.find('\0'));
  return user == kCopcUserId && loadLittleEndian<std::uint16_t>(reinterpret_cast<const std::byte*>(vlr.data()) +
                                                                kVlrRecordIdAt) == kCopcInfoRecordId;
}

CopcFile::CopcFile(std::string path) : path_(std::move(path)) {
  FileSource source(path_);
  header_ = readLasHeader(source);
  const bool layered = header_.laszip && header_.laszip->compressor == LazCompressor::kLayeredChunked;
  if (header_.format < 6 || header_.format > 8 || !layered) {
    throw source.errorAt(kPointFormatAt,
                         "a COPC file holds LAZ point formats 6 to 8 in layered chunks; this one holds " +
                             std::string(header_.compressed() ? "LAZ" : "uncompressed LAS") + " point format " +
                             std::to_string(header_.format) + " (a damaged or mislabelled file)");
  }
  readInfo(source);
  readHierarchy(source);
}

void CopcFile::readInfo(FileSource& source) {
  const std::optional<LasVlrPayload> vlr = findLasVlr(source, header_, kCopcUserId, kCopcInfoRecordId);
  if (!vlr) throw source.errorAt(header_.header_size, "no COPC info VLR (user id \"copc\", record id 1)");
  if (vlr->bytes != kInfoBytes) {
    throw source.errorAt(vlr->offset, "the COPC info VLR has " + std::to_string(vlr->bytes) + " bytes, not " +
                                          std::to_string(kInfoBytes));
  }
  info_offset_ = vlr->offset;
  std::array<std::byte, kInfoBytes> bytes{};
  source.seek(vlr->offset);
  source.readExactly(bytes, "the COPC info VLR");
  for (std::size_t a = 0; a < 3; ++a) info_.center[a] = loadLittleEndian<double>(bytes.data() + 8 * a);
  info_.halfsize = loadLittleEndian<double>(bytes.data() + 24);
  info_.spacing = loadLittleEndian<double>(bytes.data() + 32);
  info_.root_hier_offset = loadLittleEndian<std::uint64_t>(bytes.data() + 40);
  info_.root_hier_size = loadLittleEndian<std::uint64_t>(bytes.data() + 48);
  info_.gpstime_minimum = loadLittleEndian<double>(bytes.data() + 56);
  info_.gpstime_maximum = loadLittleEndian<double>(bytes.data() + 64);
  const bool finite_center =
      std::isfinite(info_.center[0]) && std::isfinite(info_.center[1]) && std::isfinite(info_.center[2]);
  if (!finite_center || !(info_.halfsize > 0.0) || !std::isfinite(info_.halfsize)) {
    throw source.errorAt(vlr->offset, "the COPC info VLR's cube (center, halfsize) is not finite and positive");
  }
  if (!(info_.spacing > 0.0) || !std::isfinite(info_.spacing)) {
    throw source.errorAt(vlr->offset + 32, "the COPC info VLR's spacing is not finite and positive");
  }
}

void CopcFile::readHierarchy(FileSource& source) {
  struct Page {
    std::uint64_t offset, bytes, pointer_at;  // pointer_at: the entry or info field that names it
  };
  std::vector<Page> pages{{info_.root_hier_offset, info_.root_hier_size, info_offset_ + 40}};
  std::unordered_set<std::uint64_t> visited;
  std::set<std::array<std::int32_t, 4>> keys_with_points;
  std::uint64_t page_bytes = 0, points = 0;
  std::vector<std::byte> page;
  while (!pages.empty()) {
    const Page at = pages.back();
    pages.pop_back();
    if (at.offset > source.size() || at.bytes > source.size() - at.offset || at.bytes % kEntryBytes != 0) {
      throw source.errorAt(at.pointer_at, "a COPC hierarchy page of " + std::to_string(at.bytes) + " bytes from byte " +
                                              std::to_string(at.offset) +
                                              " lies outside the file or is not a whole number of 32-byte entries");
    }
    // Pages never overlap, so together they fit in the file: a loop or a fan of pages over the
    // same bytes stops here instead of reading forever.
    page_bytes += at.bytes;
    if (!visited.insert(at.offset).second || page_bytes > source.size()) {
      throw source.errorAt(at.pointer_at, "the COPC hierarchy page at byte " + std::to_string(at.offset) +
                                              " is listed twice or overlaps another page");
    }
    page.resize(at.bytes);
    source.seek(at.offset);
    source.readExactly(page, "a COPC hierarchy page");
    for (std::size_t e = 0; e < at.bytes / kEntryBytes; ++e) {
      const std::byte* entry = page.data() + e * kEntryBytes;
      const std::uint64_t entry_at = at.offset + e * kEntryBytes;
      CopcNode node;
      node.level = loadLittleEndian<std::int32_t>(entry);
      node.x = loadLittleEndian<std::int32_t>(entry + 4);
      node.y = loadLittleEndian<std::int32_t>(entry + 8);
      node.z = loadLittleEndian<std::int32_t>(entry + 12);
      node.offset = loadLittleEndian<std::uint64_t>(entry + 16);
      const auto byte_size = loadLittleEndian<std::int32_t>(entry + 24);
      const auto point_count = loadLittleEndian<std::int32_t>(entry + 28);
      node.entry_offset = entry_at;
      const std::string key = keyText(node.level, node.x, node.y, node.z);
      const bool in_cube = node.level >= 0 && node.level <= kMaxLevel && node.x >= 0 && node.y >= 0 && node.z >= 0 &&
                           std::max({node.x, node.y, node.z}) < (std::int64_t{1} << node.level);
      if (!in_cube) throw source.errorAt(entry_at, "the COPC hierarchy key " + key + " lies outside the octree's cube");
      if (point_count < -1 || byte_size < 0) {
        throw source.errorAt(entry_at, "the COPC hierarchy entry of " + key + " has point count " +
                                           std::to_string(point_count) + " and byte size " + std::to_string(byte_size));
      }
      node.bytes = static_cast<std::uint32_t>(byte_size);
      if (point_count == -1) {
        pages.push_back({node.offset, node.bytes, entry_at});
        node.offset = 0;  // the page's root node is listed, with its points, in that page
        node.bytes = 0;
      } else if (point_count > 0) {
        node.points = static_cast<std::uint32_t>(point_count);
        const std::uint64_t chunks_begin = header_.point_offset + kChunkTableOffsetBytes;
        if (node.points > header_.point_count || node.points > kMaxNodePoints) {
          throw source.errorAt(entry_at, "the COPC node " + key + " claims " + std::to_string(node.points) +
                                             " points, more than the file's " + std::to_string(header_.point_count) +
                                             " or than a node may hold (" + std::to_string(kMaxNodePoints) + ")");
        }
        if (node.offset < chunks_begin || node.offset > header_.compressed_end ||
            node.bytes > header_.compressed_end - node.offset || node.bytes < header_.record_length) {
          throw source.errorAt(entry_at, "the chunk of COPC node " + key + " (" + std::to_string(node.bytes) +
                                             " bytes from byte " + std::to_string(node.offset) +
                                             ") lies outside the point data, which ends at byte " +
                                             std::to_string(header_.compressed_end));
        }
        if (!keys_with_points.insert({node.level, node.x, node.y, node.z}).second) {
          throw source.errorAt(entry_at, "the COPC node " + key + " is listed twice");
        }
        points += node.points;
      } else {
        node.offset = 0;
        node.bytes = 0;
      }
      nodes_.push_back(node);
    }
  }
  if (points != header_.point_count) {
    throw source.errorAt(info_.root_hier_offset, "the COPC hierarchy holds " + std::to_string(points) +
                                                     " points, the header says " + std::to_string(header_.point_count));
  }
}

void CopcFile::readNode(const CopcNode& node, std::vector<PointRecord>& points) const {
  points.clear();
  if (node.points == 0) return;
  FileSource source(path_);
  LazChunkTable table;
  table.chunks_start = node.offset;
  table.present = true;
  table.chunks.push_back({node.offset, node.bytes, node.points});
  LazPointDecompressor decompressor(source, *header_.laszip, std::move(table), header_.record_length);
  std::vector<std::byte> records(std::size_t{node.points} * header_.record_length);
  decompressor.decode(records);
  points.reserve(node.points);
  for (std::size_t i = 0; i < node.points; ++i) {
    points.push_back(decodeLasPoint(records.data() + i * header_.record_length, header_));
  }
}

std::string CopcFile::format() const {
  return "COPC 1.0, LAZ " + header_.version() + " point format " + std::to_string(header_.format);
}

}  // namespace plumb::io
