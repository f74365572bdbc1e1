// LAS and LAZ reader (ASPRS LAS Specification 1.4 R15, 2019; also reads LAS 1.0 to 1.3, whose
// headers are prefixes of the 1.4 one). Point data record formats 0 to 10 uncompressed; LAZ
// (compressed LAS) written with the point-wise LASzip coder, point formats 0 to 3, or the layered
// one, point formats 6 to 8 (laz_point_decompressor.h).
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
//   4. Choose the point count (below) and check at open time that the file holds every declared
//      record (LAZ: that the chunk table covers them), so that a truncated file fails before any
//      point is delivered.
//   5. Seek to the point data (skipping the VLRs whatever their number and size) and stream the
//      records in chunks through FileSource (LAZ: decompressed into the same record bytes),
//      decoding x y z (X * scale + offset), intensity and, for formats 2 3 5 7 8 10, colour
//      (already 16-bit in LAS). Bytes beyond the format's standard size ("extra bytes") are
//      skipped; whatever follows the last declared record (EVLRs in 1.4, waveform data, LAZ's
//      chunk table) is not point data and is never read as points.
//
// Point count: before 1.4 the legacy 32-bit count (header byte 107) is the count. In 1.4 the
// 64-bit count (byte 247) is the count whenever the legacy count is 0 or disagrees with it (the
// legacy count must be 0 for formats 6 to 10 and for more than 2^32 - 1 points), except when the
// 64-bit count is 0 and the legacy one is not: a writer that filled only the legacy field.
//
// Lenient on purpose: a point format newer than the version allows (format 6 in a 1.2 file, say)
// is read, since nothing in the record layout depends on the version.

#include "engine/io/las_reader.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cassert>
#include <charconv>
#include <cmath>
#include <cstring>
#include <limits>
#include <memory>
#include <optional>
#include <string_view>

#include "engine/io/byte_order.h"
#include "engine/io/file_source.h"
#include "engine/io/laszip_vlr.h"
#include "engine/io/laz_point_decompressor.h"
#include "engine/io/point_reader.h"

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

// Read chunk: enough records to amortise the calls, bounded in bytes whatever the record length.
constexpr std::size_t kChunkBytes = std::size_t{1} << 20;

// Beyond this many bytes of point data (an exbibyte) a count is corruption, not a big scan.
constexpr std::uint64_t kAbsurdPointBytes = std::uint64_t{1} << 60;

struct FormatLayout {
  std::uint16_t bytes;      // standard record size
  std::uint16_t colour_at;  // offset of red, green, blue (uint16 each) when has_colour
  bool has_colour;
  bool has_gps_time;
  bool has_wave_packet;
  bool has_nir;
};

// LAS 1.4 R15, tables 7 to 17. Formats 6 to 10 are the "extended" ones (16-bit scan angle,
// classification flags in their own byte, scanner channel).
constexpr std::array<FormatLayout, kMaxPointFormat + 1> kFormats{{
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

std::vector<std::string> ignoredFields(std::uint8_t format, std::size_t extra_bytes) {
  const FormatLayout& layout = kFormats[format];
  std::vector<std::string> fields{"return_number",       "number_of_returns", "scan_direction",
                                  "edge_of_flight_line", "classification",    "classification_flags"};
  if (format >= 6) fields.emplace_back("scanner_channel");
  fields.emplace_back(format >= 6 ? "scan_angle" : "scan_angle_rank");
  fields.emplace_back("user_data");
  fields.emplace_back("point_source_id");
  if (layout.has_gps_time) fields.emplace_back("gps_time");
  if (layout.has_nir) fields.emplace_back("nir");
  if (layout.has_wave_packet) fields.emplace_back("wave_packet");
  if (extra_bytes > 0) fields.push_back("extra bytes (" + std::to_string(extra_bytes) + " per point)");
  return fields;
}

class LasReader final : public LasPointReader {
 public:
  explicit LasReader(const std::string& path) : LasPointReader(path), source_(path) {
    readHeader();
    source_.seek(point_offset_);
    chunk_records_ = std::max<std::size_t>(1, kChunkBytes / record_length_);
  }

  bool read(PointBatch& batch, std::size_t max_points) override {
    assert(max_points > 0 && "read() needs room for at least one point; pass max_points >= 1");
    batch.clear();
    while (batch.size() < max_points && next_record_ < point_count_) {
      const std::size_t records = readRecords(records_, std::min(max_points - batch.size(), chunk_records_));
      for (std::size_t i = 0; i < records; ++i) decode(records_.data() + i * record_length_, batch);
    }
    return batch.size() > 0;
  }

  std::size_t recordLength() const override { return record_length_; }

  std::size_t readRecords(std::vector<std::byte>& records, std::size_t max_records) override {
    assert(max_records > 0 && "readRecords() needs room for at least one record; pass max_records >= 1");
    const auto count = static_cast<std::size_t>(std::min<std::uint64_t>(max_records, point_count_ - next_record_));
    records.resize(count * record_length_);
    if (laz_) {
      laz_->decode(records);
    } else {
      source_.readExactly(records, "the point records");
    }
    next_record_ += count;
    return count;
  }

 private:
  void readHeader();
  std::optional<std::uint64_t> findLaszipVlr(std::uint64_t header_size, std::uint32_t vlr_count);
  LaszipVlr readLaszipVlrAt(std::uint64_t at, std::uint8_t format);
  void decode(const std::byte* record, PointBatch& batch);

  FileSource source_;
  std::uint64_t point_offset_ = 0;
  std::size_t record_length_ = 0;
  FormatLayout layout_{};
  std::array<double, 3> scale_{}, offset_{};
  std::uint64_t point_count_ = 0;
  std::uint64_t next_record_ = 0;
  std::size_t chunk_records_ = 1;
  std::vector<std::byte> records_;
  std::unique_ptr<LazPointDecompressor> laz_;  // LAZ only; reads through source_
};

void LasReader::readHeader() {
  // Steps 1 to 4 of the file comment.
  std::array<std::byte, kHeaderBytes14> header{};
  const std::size_t got = source_.readSome(header);
  if (got == 0) {
    throw fileError(path_, "the file is empty; a LAS or LAZ file starts with a header of at least 227 bytes");
  }
  if (got < 4 || std::memcmp(header.data(), "LASF", 4) != 0) {
    throw source_.errorAt(
        0, "not a LAS or LAZ file: it does not start with \"LASF\" (wrong extension, or a damaged file)");
  }
  if (got < kHeaderBytes12) {
    throw source_.errorAt(got, "truncated header: the file ends after " + std::to_string(got) +
                                   " bytes, inside the LAS/LAZ public header (at least 227 bytes)");
  }

  const auto major = loadLittleEndian<std::uint8_t>(header.data() + kVersionMajorAt);
  const auto minor = loadLittleEndian<std::uint8_t>(header.data() + kVersionMinorAt);
  const std::string version = std::to_string(major) + "." + std::to_string(minor);
  if (major != 1 || minor > 4) {
    throw source_.errorAt(kVersionMajorAt,
                          "unknown LAS version " + version + "; Plumb reads LAS 1.0 to 1.4 (a newer or damaged file)");
  }
  const std::size_t required = minor >= 4 ? kHeaderBytes14 : minor == 3 ? kHeaderBytes13 : kHeaderBytes12;
  const auto header_size = loadLittleEndian<std::uint16_t>(header.data() + kHeaderSizeAt);
  if (header_size < required) {
    throw source_.errorAt(kHeaderSizeAt, "header size " + std::to_string(header_size) + " is smaller than the " +
                                             std::to_string(required) + " bytes LAS " + version +
                                             " requires (a corrupt header, or a wrong version number)");
  }
  if (header_size > source_.size()) {
    throw source_.errorAt(source_.size(), "truncated header: the header declares " + std::to_string(header_size) +
                                              " bytes but the file has only " + std::to_string(source_.size()));
  }

  const auto format_byte = loadLittleEndian<std::uint8_t>(header.data() + kPointFormatAt);
  const bool laz_bits = (format_byte & kLazFormatBits) != 0;
  const auto format = static_cast<std::uint8_t>(format_byte & ~kLazFormatBits);
  const auto vlr_count = loadLittleEndian<std::uint32_t>(header.data() + kVlrCountAt);
  point_offset_ = loadLittleEndian<std::uint32_t>(header.data() + kPointOffsetAt);

  if (format > kMaxPointFormat) {
    throw source_.errorAt(kPointFormatAt, "unknown point data format " + std::to_string(format) +
                                              (laz_bits ? " (byte " + std::to_string(format_byte) + ")" : "") +
                                              "; LAS 1.4 defines formats 0 to 10 (a newer or corrupt file)");
  }
  layout_ = kFormats[format];
  if (point_offset_ < header_size) {
    throw source_.errorAt(kPointOffsetAt, "offset to point data " + std::to_string(point_offset_) +
                                              " lies inside the " + std::to_string(header_size) +
                                              "-byte header; the header is corrupt");
  }
  if (point_offset_ > source_.size()) {
    throw source_.errorAt(kPointOffsetAt, "offset to point data " + std::to_string(point_offset_) +
                                              " is beyond the end of the file (" + std::to_string(source_.size()) +
                                              " bytes); the file is truncated or the header corrupt");
  }
  record_length_ = loadLittleEndian<std::uint16_t>(header.data() + kRecordLengthAt);
  if (record_length_ < layout_.bytes) {
    throw source_.errorAt(kRecordLengthAt, "point data record length " + std::to_string(record_length_) +
                                               " is shorter than the " + std::to_string(layout_.bytes) +
                                               " bytes point format " + std::to_string(format) +
                                               " needs; the header is corrupt");
  }

  // Step 2: the laszip VLR, if any, says whether and how the points are compressed.
  std::optional<LaszipVlr> laszip;
  if (const std::optional<std::uint64_t> at = findLaszipVlr(header_size, vlr_count)) {
    laszip = readLaszipVlrAt(*at, format);
  } else if (laz_bits) {
    throw source_.errorAt(kPointFormatAt, "the point format byte " + std::to_string(format_byte) +
                                              " marks a LAZ file (format " + std::to_string(format) +
                                              " with a compression bit set) but there is no laszip VLR to say how "
                                              "its points are compressed: a damaged LAZ header (or one from an "
                                              "experimental LASzip)");
  }
  const bool compressed = laszip && laszip->compressor != LazCompressor::kNone;

  const std::uint64_t legacy_count = loadLittleEndian<std::uint32_t>(header.data() + kLegacyCountAt);
  point_count_ = legacy_count;
  if (minor >= 4) {
    const auto count64 = loadLittleEndian<std::uint64_t>(header.data() + kPointCountAt);
    if (count64 != 0) point_count_ = count64;
  }
  const std::uint64_t room = (source_.size() - point_offset_) / record_length_;
  if (point_count_ > kAbsurdPointBytes / record_length_) {
    throw source_.errorAt(minor >= 4 ? kPointCountAt : kLegacyCountAt,
                          "absurd point count " + std::to_string(point_count_) +
                              (compressed ? std::string() : " (the file has room for " + std::to_string(room) + ")") +
                              "; the header is corrupt");
  }
  if (compressed) {
    // The points end at the EVLRs (LAS 1.4), else at the end of the file.
    std::uint64_t data_end = source_.size();
    if (minor >= 4 && loadLittleEndian<std::uint32_t>(header.data() + kEvlrCountAt) > 0) {
      const auto evlr_start = loadLittleEndian<std::uint64_t>(header.data() + kEvlrStartAt);
      if (evlr_start >= point_offset_ && evlr_start < data_end) data_end = evlr_start;
    }
    laz_ =
        std::make_unique<LazPointDecompressor>(source_, *laszip, point_offset_, data_end, record_length_, point_count_);
  } else if (point_count_ > room) {
    throw source_.errorAt(point_offset_ + room * record_length_,
                          "truncated point data: the header declares " + std::to_string(point_count_) + " points of " +
                              std::to_string(record_length_) + " bytes from byte " + std::to_string(point_offset_) +
                              " but only " + std::to_string(room) + " fit in the file (" +
                              std::to_string(source_.size()) + " bytes); copy or export the file again");
  }

  for (std::size_t axis = 0; axis < 3; ++axis) {
    scale_[axis] = loadLittleEndian<double>(header.data() + kScaleAt + 8 * axis);
    offset_[axis] = loadLittleEndian<double>(header.data() + kOffsetAt + 8 * axis);
    if (!std::isfinite(scale_[axis]) || scale_[axis] == 0.0 || !std::isfinite(offset_[axis])) {
      throw source_.errorAt(kScaleAt + 8 * axis, std::string("the ") + "xyz"[axis] +
                                                     " scale factor or offset is zero or not finite (scale " +
                                                     shortest(scale_[axis]) + ", offset " + shortest(offset_[axis]) +
                                                     "); the header is corrupt");
    }
  }
  Bounds bounds{};
  bool bounds_finite = true;
  for (std::size_t axis = 0; axis < 3; ++axis) {
    bounds.max[axis] = loadLittleEndian<double>(header.data() + kMaxXAt + 16 * axis);
    bounds.min[axis] = loadLittleEndian<double>(header.data() + kMaxXAt + 16 * axis + 8);
    bounds_finite = bounds_finite && std::isfinite(bounds.min[axis]) && std::isfinite(bounds.max[axis]);
  }

  info_.format = std::string(compressed ? "LAZ " : "LAS ") + version + " point format " + std::to_string(format);
  info_.declared_points = point_count_;
  if (bounds_finite) info_.declared_bounds = bounds;
  info_.attributes.colour = layout_.has_colour;
  info_.attributes.intensity = true;
  info_.ignored_fields = ignoredFields(format, record_length_ - layout_.bytes);
}

// Walks the VLRs between the header and the point data looking for the laszip one; returns the
// file offset of its header. VLRs that would run past the point data are malformed but not
// needed: the walk just stops there.
std::optional<std::uint64_t> LasReader::findLaszipVlr(std::uint64_t header_size, std::uint32_t vlr_count) {
  const std::uint64_t end = point_offset_;
  std::uint64_t at = header_size;
  std::array<std::byte, kVlrHeaderBytes> vlr{};
  for (std::uint32_t i = 0; i < vlr_count && at + kVlrHeaderBytes <= end; ++i) {
    source_.seek(at);
    source_.readExactly(vlr, "a variable length record header");
    // The user id is 16 characters, NUL-padded when shorter.
    std::string_view user(reinterpret_cast<const char*>(vlr.data() + kVlrUserIdAt), 16);
    user = user.substr(0, user.find('\0'));
    if (user == kLaszipUserId && loadLittleEndian<std::uint16_t>(vlr.data() + kVlrRecordIdAt) == kLaszipRecordId) {
      return at;
    }
    at += kVlrHeaderBytes + loadLittleEndian<std::uint16_t>(vlr.data() + kVlrLengthAt);
  }
  return std::nullopt;
}

LaszipVlr LasReader::readLaszipVlrAt(std::uint64_t at, std::uint8_t format) {
  std::array<std::byte, kVlrHeaderBytes> header{};
  source_.seek(at);
  source_.readExactly(header, "the laszip VLR's header");
  std::vector<std::byte> payload(loadLittleEndian<std::uint16_t>(header.data() + kVlrLengthAt));
  const std::uint64_t payload_at = at + kVlrHeaderBytes;
  if (payload_at + payload.size() > point_offset_) {
    throw source_.errorAt(at + kVlrLengthAt, "the laszip VLR (" + std::to_string(payload.size()) + " bytes from byte " +
                                                 std::to_string(payload_at) +
                                                 ") runs past the start of the point data at byte " +
                                                 std::to_string(point_offset_) + ": a corrupt LAZ header");
  }
  source_.readExactly(payload, "the laszip VLR");
  return readLaszipVlr(payload, payload_at, source_, format, record_length_);
}

void LasReader::decode(const std::byte* record, PointBatch& batch) {
  PointRecord point{};
  point.x = static_cast<double>(loadLittleEndian<std::int32_t>(record)) * scale_[0] + offset_[0];
  point.y = static_cast<double>(loadLittleEndian<std::int32_t>(record + 4)) * scale_[1] + offset_[1];
  point.z = static_cast<double>(loadLittleEndian<std::int32_t>(record + 8)) * scale_[2] + offset_[2];
  point.intensity = loadLittleEndian<std::uint16_t>(record + 12);
  if (layout_.has_colour) {
    for (std::size_t channel = 0; channel < 3; ++channel) {
      point.rgb[channel] = loadLittleEndian<std::uint16_t>(record + layout_.colour_at + 2 * channel);
    }
  }
  // Integers cannot be NaN, but a huge scale can overflow to infinity: deliver() counts those.
  deliver(batch, point);
}

}  // namespace

std::unique_ptr<PointReader> openLas(const std::string& path) {
  return std::make_unique<LasReader>(path);
}

std::unique_ptr<LasPointReader> openLasRecords(const std::string& path) {
  return std::make_unique<LasReader>(path);
}

}  // namespace plumb::io
