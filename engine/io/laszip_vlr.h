#pragma once
// The laszip VLR of a LAZ file (user id "laszip encoded", record id 22204), after the LASzip
// reference implementation, src/laszip.cpp (LASzip::unpack, check_item, setup; read, not copied).
// Little-endian payload:
//   compressor u16 (0 none, 1 point-wise, 2 point-wise chunked, 3 layered chunked), coder u16
//   (0 arithmetic), version major u8, minor u8, revision u16, options u32, chunk size u32
//   (points per chunk; 0xFFFFFFFF: variable, the chunk table gives each chunk's count), two i64
//   (special EVLRs, unused), item count u16, then per item: type u16, size u16, version u16.
//   34 bytes plus 6 per item.

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "engine/io/file_source.h"
#include "engine/io/laz_items.h"

namespace plumb::io {

inline constexpr std::string_view kLaszipUserId = "laszip encoded";
inline constexpr std::uint16_t kLaszipRecordId = 22204;

enum class LazCompressor : std::uint16_t {
  kNone = 0,              // point records stored raw
  kPointwise = 1,         // one arithmetic-coded stream, no chunks (LASzip 1.x)
  kPointwiseChunked = 2,  // chunks and a chunk table (LASzip 2.x and later)
  kLayeredChunked = 3,    // LAS 1.4 point formats 6 to 10 (LASzip 3.x); 6 to 8 are read
};

// The chunk size that marks variable chunks.
inline constexpr std::uint32_t kLazVariableChunks = 0xFFFFFFFFu;

struct LaszipVlr {
  LazCompressor compressor = LazCompressor::kNone;
  std::uint16_t coder = 0;
  std::uint8_t version_major = 0, version_minor = 0;
  std::uint16_t version_revision = 0;
  std::uint32_t chunk_size = 0;
  std::vector<LazItem> items;

  // The LASzip version that wrote the file, e.g. "LASzip 2.2r0".
  std::string writer() const;
};

// "POINT10", "GPSTIME11", ..., or "type 22" for a type LASzip does not define.
std::string lazItemName(std::uint16_t type);

// Parses and checks the VLR's payload, which starts at file offset `at` of `source`, for a file
// of LAS point format `format` (the format byte without its compression bits) and records of
// `record_length` bytes. Refuses, with plumb::Error naming the file, the offset of the field and
// what is wrong: a payload that is not 34 bytes plus 6 per item (at least one item); a compressor
// other than 0 to 3; a coder other than 0; for compressors 1 and 2, an item of unknown type, of a
// version other than 1 and 2, of the wrong size, of a kind not read (waveform packets, LAS 1.4
// items), or items that are not those of the point format and record length (POINT10, then
// GPSTIME11 for formats 1 and 3, RGB12 for 2 and 3, then BYTE for the extra bytes); for
// compressor 3, an item that is not POINT14, RGB14, RGBNIR14 or BYTE14 (WAVEPACKET14: waveforms
// are not read), of a version other than 3 and 4, of the wrong size, or items that are not those
// of point formats 6 to 8 (POINT14, then RGB14 for 7 or RGBNIR14 for 8, then BYTE14).
LaszipVlr readLaszipVlr(std::span<const std::byte> payload, std::uint64_t at, const FileSource& source, unsigned format,
                        std::size_t record_length);

}  // namespace plumb::io
