#pragma once
// A large COPC file made from a small one, for benchmarks and tests of locality: 2^k x 2^k
// copies of a tile side by side in x and y, without compressing anything. Plumb has no LAZ
// encoder, and none is needed: LAZ codes a chunk's coordinates as differences from its first
// point, which is stored raw, so moving that point's X and Y by whole units moves the whole
// chunk. Each copy's nodes go k levels down (node (L, x, y, z) of copy (i, j) becomes
// (L + k, x + i 2^L, y + j 2^L, z)); levels 0 to k - 1 are empty nodes; the info VLR's cube
// grows 2^k times, its spacing with it.
//
// For random access only: the LAZ chunk table is not rewritten (that needs the encoder), so its
// offset says "never written" and sequential readers (openLas, plumb import) refuse the file.

#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>
#include <vector>

#include "engine/io/copc_file.h"
#include "engine/io/file_source.h"

namespace plumb::test {

namespace copc_mosaic_detail {

template <typename T>
T get(const std::string& bytes, std::size_t at) {
  T value;
  std::memcpy(&value, bytes.data() + at, sizeof(T));  // little-endian, as LAS and this machine
  return value;
}
template <typename T>
void put(std::string& bytes, std::size_t at, T value) {
  std::memcpy(bytes.data() + at, &value, sizeof(T));
}
template <typename T>
void append(std::string& bytes, T value) {
  bytes.append(reinterpret_cast<const char*>(&value), sizeof(T));
}

}  // namespace copc_mosaic_detail

// Writes the mosaic of 2^levels x 2^levels copies of COPC file `tile` to `output`. Throws
// plumb::Error for a tile io::CopcFile refuses.
inline void writeCopcMosaic(const std::string& tile, int levels, const std::string& output) {
  using namespace copc_mosaic_detail;
  const io::CopcFile copc(tile);
  const io::LasHeader& las = copc.header();
  std::ifstream in(tile, std::ios::binary);
  const std::string source((std::istreambuf_iterator<char>(in)), {});
  const std::uint32_t per_axis = 1u << levels;
  const double tile_size = 2.0 * copc.info().halfsize;

  // Header and VLRs, up to the point data, patched below; then the chunk table's offset.
  std::string file = source.substr(0, las.point_offset);
  io::FileSource tile_source(tile);
  const std::uint64_t info_at = io::findLasVlr(tile_source, las, "copc", 1)->offset;
  const double halfsize = copc.info().halfsize * per_axis;
  put(file, info_at + 0, copc.info().center[0] - copc.info().halfsize + halfsize);
  put(file, info_at + 8, copc.info().center[1] - copc.info().halfsize + halfsize);
  put(file, info_at + 16, copc.info().center[2] - copc.info().halfsize + halfsize);
  put(file, info_at + 24, halfsize);
  put(file, info_at + 32, copc.info().spacing * per_axis);
  append(file, static_cast<std::int64_t>(las.point_offset));  // the chunk table: never written

  struct Entry {
    std::array<std::int32_t, 4> key;
    std::uint64_t offset;
    std::int32_t bytes, points;
  };
  std::vector<Entry> entries;
  for (int level = 0; level < levels; ++level) {
    const std::int32_t n = 1 << level;
    for (std::int32_t y = 0; y < n; ++y) {
      for (std::int32_t x = 0; x < n; ++x) entries.push_back({{level, x, y, 0}, 0, 0, 0});
    }
  }
  for (std::uint32_t j = 0; j < per_axis; ++j) {
    for (std::uint32_t i = 0; i < per_axis; ++i) {
      const std::array<std::int32_t, 2> shift{static_cast<std::int32_t>(std::llround(i * tile_size / las.scale[0])),
                                              static_cast<std::int32_t>(std::llround(j * tile_size / las.scale[1]))};
      for (const io::CopcNode& node : copc.nodes()) {
        if (node.points == 0) continue;
        std::string chunk = source.substr(node.offset, node.bytes);
        // The raw first point: X and Y are its first two int32s.
        put(chunk, 0, get<std::int32_t>(chunk, 0) + shift[0]);
        put(chunk, 4, get<std::int32_t>(chunk, 4) + shift[1]);
        const std::int32_t step = 1 << node.level;
        entries.push_back({{node.level + levels, node.x + static_cast<std::int32_t>(i) * step,
                            node.y + static_cast<std::int32_t>(j) * step, node.z},
                           file.size(),
                           static_cast<std::int32_t>(node.bytes),
                           static_cast<std::int32_t>(node.points)});
        file += chunk;
      }
    }
  }

  // The hierarchy: one EVLR (user id "copc", record id 1000), one page.
  const std::uint64_t evlr_at = file.size();
  append(file, std::uint16_t{0});
  file.append("copc", 4);
  file.append(12, '\0');
  append(file, std::uint16_t{1000});
  append(file, static_cast<std::uint64_t>(entries.size() * 32));
  file.append(32, '\0');
  const std::uint64_t page_at = file.size();
  for (const Entry& e : entries) {
    for (const std::int32_t k : e.key) append(file, k);
    append(file, e.offset);
    append(file, e.bytes);
    append(file, e.points);
  }
  put(file, info_at + 40, page_at);
  put(file, info_at + 48, static_cast<std::uint64_t>(entries.size() * 32));

  // The public header: point count (LAS 1.4's 64-bit one), bounds, the EVLRs.
  put(file, 247, las.point_count * per_axis * per_axis);
  const std::array<double, 3> min = las.bounds->min;
  put(file, 179, las.bounds->max[0] + (per_axis - 1) * tile_size);  // max x, min x, max y, min y
  put(file, 195, las.bounds->max[1] + (per_axis - 1) * tile_size);
  put(file, 187, min[0]);
  put(file, 203, min[1]);
  put(file, 235, evlr_at);
  put(file, 243, std::uint32_t{1});

  std::ofstream out(output, std::ios::binary);
  out.write(file.data(), static_cast<std::streamsize>(file.size()));
  if (!out) throw std::runtime_error("cannot write " + output);
}

}  // namespace plumb::test
