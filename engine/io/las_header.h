#pragma once
// The public header block of a LAS or LAZ file (ASPRS LAS Specification 1.4 R15, 2019, section
// 2.4; LAS 1.0 to 1.3 headers are prefixes of it), its variable length records, and the decoding
// of the fields Plumb keeps from one point record. Shared by the sequential reader
// (las_reader.cpp) and by the COPC octree, which reads the same header and then single chunks.

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "engine/io/file_source.h"
#include "engine/io/laszip_vlr.h"
#include "engine/io/point_reader.h"

namespace plumb::io {

// Where a point format keeps what Plumb reads (LAS 1.4 R15, tables 7 to 17).
struct LasFormatLayout {
  std::uint16_t bytes;      // standard record size
  std::uint16_t colour_at;  // offset of red, green, blue (uint16 each) when has_colour
  bool has_colour;
  bool has_gps_time;
  bool has_wave_packet;
  bool has_nir;
};

struct LasHeader {
  std::uint8_t version_minor = 0;  // the major version is always 1
  std::uint16_t header_size = 0;
  std::uint32_t vlr_count = 0;
  std::uint64_t point_offset = 0;
  std::uint8_t format = 0;  // without LAZ's compression bits
  LasFormatLayout layout{};
  std::size_t record_length = 0;
  std::uint64_t point_count = 0;
  std::array<double, 3> scale{}, offset{};
  std::optional<Bounds> bounds;      // absent when the header's are not finite
  std::optional<LaszipVlr> laszip;   // the laszip VLR, when the file has one
  std::uint64_t compressed_end = 0;  // LAZ: where the compressed points end (the EVLRs or the file's end)

  bool compressed() const { return laszip && laszip->compressor != LazCompressor::kNone; }
  // "1.4"
  std::string version() const { return "1." + std::to_string(version_minor); }
};

// Reads and checks the header of the file `source` reads, from its start: "LASF", version 1.0 to
// 1.4, header size, offset to point data, point format 0 to 10 and record length, the point count,
// scale, offset and bounds, and the laszip VLR (readLaszipVlr's checks). For an uncompressed file,
// also that the file holds every declared record. Throws plumb::Error naming the file, the byte
// offset and what is wrong. Leaves `source` at an unspecified offset.
LasHeader readLasHeader(FileSource& source);

// A variable length record's payload: its file offset and size in bytes.
struct LasVlrPayload {
  std::uint64_t offset = 0;
  std::uint16_t bytes = 0;
};

// Walks the VLRs between the header and the point data for the first one with `user_id` and
// `record_id`. VLRs that would run past the point data are malformed but not needed: the walk
// stops there. Throws plumb::Error only when the file cannot be read.
std::optional<LasVlrPayload> findLasVlr(FileSource& source, const LasHeader& header, std::string_view user_id,
                                        std::uint16_t record_id);

// Position (X * scale + offset), intensity and colour (formats with colour) of one record of
// `header`'s format.
PointRecord decodeLasPoint(const std::byte* record, const LasHeader& header);

}  // namespace plumb::io
