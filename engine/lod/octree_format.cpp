#include "engine/lod/octree_format.h"

#include <zlib.h>

#include <bit>
#include <cstring>

#include "engine/core/error.h"

namespace plumb::lod {
namespace {

static_assert(std::endian::native == std::endian::little, "the octree format is written on little-endian hosts");

// Sequential little-endian field writer and reader over a fixed buffer.
class Writer {
 public:
  explicit Writer(std::byte* out) : out_(out) {}
  template <typename T>
  void put(T value) {
    std::memcpy(out_, &value, sizeof(T));
    out_ += sizeof(T);
  }

 private:
  std::byte* out_;
};

class Reader {
 public:
  explicit Reader(const std::byte* in) : in_(in) {}
  template <typename T>
  T get() {
    T value;
    std::memcpy(&value, in_, sizeof(T));
    in_ += sizeof(T);
    return value;
  }

 private:
  const std::byte* in_;
};

constexpr std::size_t kHeaderCrcOffset = kHeaderBytes - 4;
constexpr std::uint64_t kFramingOffset = 192;  // version 3: the framing box, 6 x f64

}  // namespace

std::uint32_t crc32Of(std::span<const std::byte> bytes) {
  uLong crc = ::crc32(0L, Z_NULL, 0);
  // zlib takes uInt lengths: feed large blocks in pieces.
  while (!bytes.empty()) {
    const std::size_t piece = std::min<std::size_t>(bytes.size(), std::size_t{1} << 30);
    crc = ::crc32(crc, reinterpret_cast<const Bytef*>(bytes.data()), static_cast<uInt>(piece));
    bytes = bytes.subspan(piece);
  }
  return static_cast<std::uint32_t>(crc);
}

std::array<std::byte, kHeaderBytes> encodeHeader(const OctreeHeader& h) {
  std::array<std::byte, kHeaderBytes> bytes{};
  Writer w(bytes.data());
  for (char c : kOctreeMagic) w.put(c);
  w.put(kOctreeVersion);
  w.put(static_cast<std::uint32_t>(kHeaderBytes));
  w.put(h.point_count);
  w.put(h.node_count);
  for (double v : h.cube.origin) w.put(v);
  w.put(h.cube.size);
  w.put(h.root_spacing);
  w.put(h.sampling_grid);
  w.put(h.depth);
  w.put(h.attributes);
  w.put(h.leaf_max_points);
  for (double v : h.bounds.min) w.put(v);
  for (double v : h.bounds.max) w.put(v);
  w.put(h.skipped_non_finite);
  w.put(h.index_offset);
  w.put(h.index_bytes);
  w.put(h.index_crc);
  w.put(h.input_files);
  w.put(h.scan_table_offset);
  w.put(h.scan_table_bytes);
  w.put(h.scan_table_crc);
  w.put(h.scan_count);
  const Box3 framing = h.framing.value_or(h.bounds);
  for (double v : framing.min) w.put(v);
  for (double v : framing.max) w.put(v);
  const std::uint32_t crc = crc32Of(std::span(bytes).first(kHeaderCrcOffset));
  std::memcpy(bytes.data() + kHeaderCrcOffset, &crc, 4);
  return bytes;
}

OctreeHeader decodeHeader(std::span<const std::byte, kHeaderBytes> bytes, const std::string& path) {
  Reader r(bytes.data());
  std::array<char, 8> magic{};
  for (char& c : magic) c = r.get<char>();
  if (magic != kOctreeMagic) throw fileErrorAt(path, 0, "not a Plumb octree (build one with 'plumb import')");
  const auto version = r.get<std::uint32_t>();
  if (version > kOctreeVersion) {
    throw fileErrorAt(path, 8,
                      "octree format version " + std::to_string(version) + " is newer than this Plumb (" +
                          std::to_string(kOctreeVersion) + "); update Plumb");
  }
  if (version < kOldestOctreeVersion) {
    throw fileErrorAt(path, 8, "unknown octree format version " + std::to_string(version));
  }
  if (r.get<std::uint32_t>() != kHeaderBytes) throw fileErrorAt(path, 12, "unexpected header size");
  std::uint32_t stored_crc = 0;
  std::memcpy(&stored_crc, bytes.data() + kHeaderCrcOffset, 4);
  if (stored_crc != crc32Of(bytes.first(kHeaderCrcOffset))) {
    throw fileErrorAt(path, 0, "the header is corrupt (checksum mismatch); rebuild the octree with 'plumb import'");
  }
  OctreeHeader h;
  h.version = version;
  h.point_count = r.get<std::uint64_t>();
  h.node_count = r.get<std::uint64_t>();
  for (double& v : h.cube.origin) v = r.get<double>();
  h.cube.size = r.get<double>();
  h.root_spacing = r.get<double>();
  h.sampling_grid = r.get<std::uint32_t>();
  h.depth = r.get<std::uint32_t>();
  h.attributes = r.get<std::uint32_t>();
  h.leaf_max_points = r.get<std::uint32_t>();
  for (double& v : h.bounds.min) v = r.get<double>();
  for (double& v : h.bounds.max) v = r.get<double>();
  h.skipped_non_finite = r.get<std::uint64_t>();
  h.index_offset = r.get<std::uint64_t>();
  h.index_bytes = r.get<std::uint64_t>();
  h.index_crc = r.get<std::uint32_t>();
  h.input_files = r.get<std::uint32_t>();
  // Version 1 wrote zeros here.
  h.scan_table_offset = r.get<std::uint64_t>();
  h.scan_table_bytes = r.get<std::uint64_t>();
  h.scan_table_crc = r.get<std::uint32_t>();
  h.scan_count = r.get<std::uint32_t>();
  const bool scan_index = (h.attributes & kHasScanIndex) != 0;
  if (scan_index != (h.scan_count > 0) || (version < 2 && scan_index)) {
    throw fileErrorAt(path, 80, "corrupt header: the scan index flag and the scan count disagree");
  }
  if (version >= 3) {
    Box3 framing{};
    for (double& v : framing.min) v = r.get<double>();
    for (double& v : framing.max) v = r.get<double>();
    for (std::size_t a = 0; a < 3; ++a) {
      // Also false for NaN.
      if (!(h.bounds.min[a] <= framing.min[a] && framing.min[a] <= framing.max[a] &&
            framing.max[a] <= h.bounds.max[a])) {
        throw fileErrorAt(path, kFramingOffset, "corrupt header: the framing box does not lie inside the bounds");
      }
    }
    h.framing = framing;
  }
  return h;
}

void encodeIndexEntry(const NodeInfo& node, std::byte* out) {
  Writer w(out);
  w.put(node.key.level);
  w.put(node.key.x);
  w.put(node.key.y);
  w.put(node.key.z);
  w.put(node.point_count);
  w.put(node.crc);
  w.put(node.offset);
  w.put(node.child_mask);
  for (int i = 0; i < 7; ++i) w.put(std::uint8_t{0});
}

NodeInfo decodeIndexEntry(const std::byte* in, std::uint32_t attributes) {
  Reader r(in);
  NodeInfo node;
  node.key.level = r.get<std::uint32_t>();
  node.key.x = r.get<std::uint32_t>();
  node.key.y = r.get<std::uint32_t>();
  node.key.z = r.get<std::uint32_t>();
  node.point_count = r.get<std::uint32_t>();
  node.crc = r.get<std::uint32_t>();
  node.offset = r.get<std::uint64_t>();
  node.child_mask = r.get<std::uint8_t>();
  node.bytes = nodeBlockBytes(node.point_count, attributes);
  return node;
}

std::vector<std::byte> encodeScanTable(const std::vector<std::string>& names) {
  std::size_t size = 0;
  for (const std::string& name : names) size += 4 + name.size();
  std::vector<std::byte> bytes(size);
  std::byte* out = bytes.data();
  for (const std::string& name : names) {
    const auto length = static_cast<std::uint32_t>(name.size());
    std::memcpy(out, &length, 4);
    std::memcpy(out + 4, name.data(), name.size());
    out += 4 + name.size();
  }
  return bytes;
}

std::vector<std::string> decodeScanTable(std::span<const std::byte> bytes, std::uint32_t count, const std::string& path,
                                         std::uint64_t offset) {
  std::vector<std::string> names;
  std::size_t at = 0;
  for (std::uint32_t i = 0; i < count; ++i) {
    if (bytes.size() - at < 4)
      throw fileErrorAt(path, offset + at, "corrupt scan table: it ends before scan " + std::to_string(i));
    std::uint32_t length = 0;
    std::memcpy(&length, bytes.data() + at, 4);
    if (bytes.size() - at - 4 < length) {
      throw fileErrorAt(path, offset + at,
                        "corrupt scan table: the name of scan " + std::to_string(i) + " (" + std::to_string(length) +
                            " bytes) runs past the table");
    }
    names.emplace_back(reinterpret_cast<const char*>(bytes.data() + at + 4), length);
    at += 4 + length;
  }
  if (at != bytes.size()) throw fileErrorAt(path, offset + at, "corrupt scan table: bytes after its last scan");
  return names;
}

void encodePoint(const PackedPoint& p, std::byte* out) {
  Writer w(out);
  w.put(p.x);
  w.put(p.y);
  w.put(p.z);
  for (std::uint16_t c : p.rgb) w.put(c);
  w.put(p.intensity);
}

PackedPoint decodePoint(const std::byte* in) {
  Reader r(in);
  PackedPoint p;
  p.x = r.get<float>();
  p.y = r.get<float>();
  p.z = r.get<float>();
  for (std::uint16_t& c : p.rgb) c = r.get<std::uint16_t>();
  p.intensity = r.get<std::uint16_t>();
  return p;
}

}  // namespace plumb::lod
