// The LAS public header block (ASPRS LAS Specification 1.4 R15, 2019, section 2.4, table 3).
//
//   1. Read the public header block: "LASF", version 1.0 to 1.4, header size (at least 227
//      bytes, 235 for 1.3, 375 for 1.4), offset to point data, point format and record length,
//      the point counts, scale, offset and bounds.
//   2. LAZ: the point format byte has bit 7 (or 6) set, and a VLR with user id "laszip encoded"
//      (record id 22204) says how the points are compressed (laszip_vlr.h). As in the LASzip
//      reference implementation, that VLR decides: a file that has it is read as LAZ, whatever
//      the format byte's bits; bits without it are an error.
//   3. Validate the layout: point format 0 to 10 (without the LAZ bits), offset to point data
//      between the end of the header and the end of the file, record length at least the
//      format's standard size.
//   4. Choose the point count (below) and, uncompressed, check that the file holds every
//      declared record, so that a truncated file fails before any point is delivered.
//
// Point count: before 1.4 the legacy 32-bit count (header byte 107) is the count. In 1.4 the
// 64-bit count (byte 247) is the count whenever the legacy count is 0 or disagrees with it (the
// legacy count must be 0 for formats 6 to 10 and for more than 2^32 - 1 points), except when the
// 64-bit count is 0 and the legacy one is not: a writer that filled only the legacy field.
//
// Lenient on purpose: a point format newer than the version allows (format 6 in a 1.2 file, say)
// is read, since nothing in the record layout depends on the version.

#include "engine/io/las_header.h"

#include <charconv>
#include <cmath>
#include <cstring>
#include <vector>

#include "engine/io/byte_order.h"

namespace plumb::io {
namespace {

// Header sizes: up to "Min Z" (1.0 to 1.2), plus the waveform start (1.3), plus the EVLR fields
// and the 64-bit counts (1.4).
constexpr std::size_t kHeaderBytes12 = 227;
constexpr std::size_t kHeaderBytes13 = 235;
constexpr std::size_t kHeaderBytes14 = 375;

// Byte offsets of the public header fields used here (LAS 1.4 R15, table 3).
constexpr std::size_t kVersionMajorAt = 24;
constexpr std::size_t kVersionMinorAt = 25;
constexpr std::size_t kHeaderSizeAt = 94;
constexpr std::size_t kPointOffsetAt = 96;
constexpr std::size_t kVlrCountAt = 100;
constexpr std::size_t kPointFormatAt = 104;
constexpr std::size_t kRecordLengthAt = 105;
constexpr std::size_t kLegacyCountAt = 107;
constexpr std::size_t kScaleAt = 131;      // x y z doubles
constexpr std::size_t kOffsetAt = 155;     // x y z doubles
constexpr std::size_t kMaxXAt = 179;       // max x, min x, max y, min y, max z, min z
constexpr std::size_t kEvlrStartAt = 235;  // 1.4: u64 offset of the first EVLR, u32 count
constexpr std::size_t kEvlrCountAt = 243;
constexpr std::size_t kPointCountAt = 247;

// VLR header: reserved (2), user id (16), record id (2), record length after header (2),
// description (32).
constexpr std::size_t kVlrHeaderBytes = 54;
constexpr std::size_t kVlrUserIdAt = 2;
constexpr std::size_t kVlrRecordIdAt = 18;
constexpr std::size_t kVlrLengthAt = 20;

constexpr std::uint8_t kLazFormatBits = 0xC0;
constexpr std::uint8_t kMaxPointFormat = 10;

// Beyond this many bytes of point data (an exbibyte) a count is corruption, not a big scan.
constexpr std::uint64_t kAbsurdPointBytes = std::uint64_t{1} << 60;

// LAS 1.4 R15, tables 7 to 17. Formats 6 to 10 are the "extended" ones (16-bit scan angle,
// classification flags in their own byte, scanner channel).
constexpr std::array<LasFormatLayout, kMaxPointFormat + 1> kFormats{{
    {20, 0, false, false, false, false},  // 0
    {28, 0, false, true, false, false},   // 1
    {26, 20, true, false, false, false},  // 2
    {34, 28, true, true, false, false},   // 3
    {57, 0, false, true, true, false},    // 4
    {63, 28, true, true, true, false},    // 5
    {30, 0, false, true, false, false},   // 6
    {36, 30, true, true, false, false},   // 7
    {38, 30, true, true, false, true},    // 8
    {59, 0, false, true, true, false},    // 9
    {67, 30, true, true, true, true},     // 10
}};

// The shortest text that reads back as `value` ("0.001", not "0.001000").
std::string shortest(double value) {
  std::array<char, 32> text{};
  const auto result = std::to_chars(text.data(), text.data() + text.size(), value);
  return std::string(text.data(), result.ptr);
}

LaszipVlr readLaszipVlrAt(FileSource& source, const LasHeader& header, const LasVlrPayload& vlr) {
  if (vlr.offset + vlr.bytes > header.point_offset) {
    throw source.errorAt(vlr.offset - kVlrHeaderBytes + kVlrLengthAt,
                         "the laszip VLR (" + std::to_string(vlr.bytes) + " bytes from byte " +
                             std::to_string(vlr.offset) + ") runs past the start of the point data at byte " +
                             std::to_string(header.point_offset) + ": a corrupt LAZ header");
  }
  std::vector<std::byte> payload(vlr.bytes);
  source.seek(vlr.offset);
  source.readExactly(payload, "the laszip VLR");
  return readLaszipVlr(payload, vlr.offset, source, header.format, header.record_length);
}

}  // namespace

LasHeader readLasHeader(FileSource& source) {
  LasHeader result;
  std::array<std::byte, kHeaderBytes14> header{};
  source.seek(0);
  const std::size_t got = source.readSome(header);
  if (got == 0) {
    throw fileError(source.path(), "the file is empty; a LAS or LAZ file starts with a header of at least 227 bytes");
  }
  if (got < 4 || std::memcmp(header.data(), "LASF", 4) != 0) {
    throw source.errorAt(0,
                         "not a LAS or LAZ file: it does not start with \"LASF\" (wrong extension, or a damaged file)");
  }
  if (got < kHeaderBytes12) {
    throw source.errorAt(got, "truncated header: the file ends after " + std::to_string(got) +
                                  " bytes, inside the LAS/LAZ public header (at least 227 bytes)");
  }

  const auto major = loadLittleEndian<std::uint8_t>(header.data() + kVersionMajorAt);
  const auto minor = loadLittleEndian<std::uint8_t>(header.data() + kVersionMinorAt);
  const std::string version = std::to_string(major) + "." + std::to_string(minor);
  if (major != 1 || minor > 4) {
    throw source.errorAt(kVersionMajorAt,
                         "unknown LAS version " + version + "; Plumb reads LAS 1.0 to 1.4 (a newer or damaged file)");
  }
  result.version_minor = minor;
  const std::size_t required = minor >= 4 ? kHeaderBytes14 : minor == 3 ? kHeaderBytes13 : kHeaderBytes12;
  result.header_size = loadLittleEndian<std::uint16_t>(header.data() + kHeaderSizeAt);
  if (result.header_size < required) {
    throw source.errorAt(kHeaderSizeAt, "header size " + std::to_string(result.header_size) + " is smaller than the " +
                                            std::to_string(required) + " bytes LAS " + version +
                                            " requires (a corrupt header, or a wrong version number)");
  }
  if (result.header_size > source.size()) {
    throw source.errorAt(source.size(), "truncated header: the header declares " + std::to_string(result.header_size) +
                                            " bytes but the file has only " + std::to_string(source.size()));
  }

  const auto format_byte = loadLittleEndian<std::uint8_t>(header.data() + kPointFormatAt);
  const bool laz_bits = (format_byte & kLazFormatBits) != 0;
  result.format = static_cast<std::uint8_t>(format_byte & ~kLazFormatBits);
  result.vlr_count = loadLittleEndian<std::uint32_t>(header.data() + kVlrCountAt);
  result.point_offset = loadLittleEndian<std::uint32_t>(header.data() + kPointOffsetAt);

  if (result.format > kMaxPointFormat) {
    throw source.errorAt(kPointFormatAt, "unknown point data format " + std::to_string(result.format) +
                                             (laz_bits ? " (byte " + std::to_string(format_byte) + ")" : "") +
                                             "; LAS 1.4 defines formats 0 to 10 (a newer or corrupt file)");
  }
  result.layout = kFormats[result.format];
  if (result.point_offset < result.header_size) {
    throw source.errorAt(kPointOffsetAt, "offset to point data " + std::to_string(result.point_offset) +
                                             " lies inside the " + std::to_string(result.header_size) +
                                             "-byte header; the header is corrupt");
  }
  if (result.point_offset > source.size()) {
    throw source.errorAt(kPointOffsetAt, "offset to point data " + std::to_string(result.point_offset) +
                                             " is beyond the end of the file (" + std::to_string(source.size()) +
                                             " bytes); the file is truncated or the header corrupt");
  }
  result.record_length = loadLittleEndian<std::uint16_t>(header.data() + kRecordLengthAt);
  if (result.record_length < result.layout.bytes) {
    throw source.errorAt(kRecordLengthAt, "point data record length " + std::to_string(result.record_length) +
                                              " is shorter than the " + std::to_string(result.layout.bytes) +
                                              " bytes point format " + std::to_string(result.format) +
                                              " needs; the header is corrupt");
  }

  // Step 2: the laszip VLR, if any, says whether and how the points are compressed.
  if (const std::optional<LasVlrPayload> vlr = findLasVlr(source, result, kLaszipUserId, kLaszipRecordId)) {
    result.laszip = readLaszipVlrAt(source, result, *vlr);
  } else if (laz_bits) {
    throw source.errorAt(kPointFormatAt, "the point format byte " + std::to_string(format_byte) +
                                             " marks a LAZ file (format " + std::to_string(result.format) +
                                             " with a compression bit set) but there is no laszip VLR to say how "
                                             "its points are compressed: a damaged LAZ header (or one from an "
                                             "experimental LASzip)");
  }

  const std::uint64_t legacy_count = loadLittleEndian<std::uint32_t>(header.data() + kLegacyCountAt);
  result.point_count = legacy_count;
  if (minor >= 4) {
    const auto count64 = loadLittleEndian<std::uint64_t>(header.data() + kPointCountAt);
    if (count64 != 0) result.point_count = count64;
  }
  const std::uint64_t room = (source.size() - result.point_offset) / result.record_length;
  if (result.point_count > kAbsurdPointBytes / result.record_length) {
    throw source.errorAt(
        minor >= 4 ? kPointCountAt : kLegacyCountAt,
        "absurd point count " + std::to_string(result.point_count) +
            (result.compressed() ? std::string() : " (the file has room for " + std::to_string(room) + ")") +
            "; the header is corrupt");
  }
  if (result.compressed()) {
    // The points end at the EVLRs (LAS 1.4), else at the end of the file.
    result.compressed_end = source.size();
    if (minor >= 4 && loadLittleEndian<std::uint32_t>(header.data() + kEvlrCountAt) > 0) {
      const auto evlr_start = loadLittleEndian<std::uint64_t>(header.data() + kEvlrStartAt);
      if (evlr_start >= result.point_offset && evlr_start < result.compressed_end) result.compressed_end = evlr_start;
    }
  } else if (result.point_count > room) {
    throw source.errorAt(result.point_offset + room * result.record_length,
                         "truncated point data: the header declares " + std::to_string(result.point_count) +
                             " points of " + std::to_string(result.record_length) + " bytes from byte " +
                             std::to_string(result.point_offset) + " but only " + std::to_string(room) +
                             " fit in the file (" + std::to_string(source.size()) +
                             " bytes); copy or export the file again");
  }

  for (std::size_t axis = 0; axis < 3; ++axis) {
    result.scale[axis] = loadLittleEndian<double>(header.data() + kScaleAt + 8 * axis);
    result.offset[axis] = loadLittleEndian<double>(header.data() + kOffsetAt + 8 * axis);
    if (!std::isfinite(result.scale[axis]) || result.scale[axis] == 0.0 || !std::isfinite(result.offset[axis])) {
      throw source.errorAt(kScaleAt + 8 * axis, std::string("the ") + "xyz"[axis] +
                                                    " scale factor or offset is zero or not finite (scale " +
                                                    shortest(result.scale[axis]) + ", offset " +
                                                    shortest(result.offset[axis]) + "); the header is corrupt");
    }
  }
  Bounds bounds{};
  bool bounds_finite = true;
  for (std::size_t axis = 0; axis < 3; ++axis) {
    bounds.max[axis] = loadLittleEndian<double>(header.data() + kMaxXAt + 16 * axis);
    bounds.min[axis] = loadLittleEndian<double>(header.data() + kMaxXAt + 16 * axis + 8);
    bounds_finite = bounds_finite && std::isfinite(bounds.min[axis]) && std::isfinite(bounds.max[axis]);
  }
  if (bounds_finite) result.bounds = bounds;
  return result;
}

std::optional<LasVlrPayload> findLasVlr(FileSource& source, const LasHeader& header, std::string_view user_id,
                                        std::uint16_t record_id) {
  const std::uint64_t end = header.point_offset;
  std::uint64_t at = header.header_size;
  std::array<std::byte, kVlrHeaderBytes> vlr{};
  for (std::uint32_t i = 0; i < header.vlr_count && at + kVlrHeaderBytes <= end; ++i) {
    source.seek(at);
    source.readExactly(vlr, "a variable length record header");
    // The user id is 16 characters, NUL-padded when shorter.
    std::string_view user(reinterpret_cast<const char*>(vlr.data() + kVlrUserIdAt), 16);
    user = user.substr(0, user.find('\0'));
    const auto bytes = loadLittleEndian<std::uint16_t>(vlr.data() + kVlrLengthAt);
    if (user == user_id && loadLittleEndian<std::uint16_t>(vlr.data() + kVlrRecordIdAt) == record_id) {
      return LasVlrPayload{at + kVlrHeaderBytes, bytes};
    }
    at += kVlrHeaderBytes + bytes;
  }
  return std::nullopt;
}

PointRecord decodeLasPoint(const std::byte* record, const LasHeader& header) {
  PointRecord point{};
  point.x = static_cast<double>(loadLittleEndian<std::int32_t>(record)) * header.scale[0] + header.offset[0];
  point.y = static_cast<double>(loadLittleEndian<std::int32_t>(record + 4)) * header.scale[1] + header.offset[1];
  point.z = static_cast<double>(loadLittleEndian<std::int32_t>(record + 8)) * header.scale[2] + header.offset[2];
  point.intensity = loadLittleEndian<std::uint16_t>(record + 12);
  if (header.layout.has_colour) {
    for (std::size_t channel = 0; channel < 3; ++channel) {
      point.rgb[channel] = loadLittleEndian<std::uint16_t>(record + header.layout.colour_at + 2 * channel);
    }
  }
  return point;
}

}  // namespace plumb::io
