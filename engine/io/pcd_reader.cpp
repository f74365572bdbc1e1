// PCD reader (the Point Cloud Library's point cloud data format, versions 0.7 and 0.6).
//
//   1. Read the header lines (VERSION FIELDS SIZE TYPE COUNT WIDTH HEIGHT VIEWPOINT POINTS, in any
//      order, then DATA last; lines starting with '#' are comments), remembering each line's number.
//   2. Check the header: FIELDS, SIZE, TYPE and COUNT of equal length, a valid SIZE for each
//      TYPE (F 4/8, I and U 1/2/4/8), WIDTH x HEIGHT = POINTS, a known DATA kind.
//   3. Lay out a record (each field's byte offset, SIZE x COUNT bytes per field) and map fields to
//      roles by name: x y z (required), packed "rgb" or "rgba", "intensity", normal_x/y/z. The rest
//      is listed in CloudInfo::ignored_fields ("_", PCL's padding, is skipped without a listing).
//   4. By DATA kind:
//      ascii              one point per line, checked as it is read; after the last point only
//                         blank lines may follow.
//      binary             little-endian records; the file size must hold exactly POINTS records
//                         (checked at open, so a truncated file fails before any point is used),
//                         streamed in batches.
//      binary_compressed  two uint32 (compressed and uncompressed size), then one LZF block whose
//                         content is structure-of-arrays (all values of the first field, then the
//                         second...). It cannot be streamed: the sizes are checked, the block is
//                         decompressed into memory once, and batches are cut from there. Zeros
//                         may follow the block (PCL pads its files), nothing else.
//   5. Skip points with a non-finite coordinate (organized clouds mark invalid pixels with NaN),
//      counting them in ReadCounts::non_finite.
//
// Colour: "rgb" holds 0x00RRGGBB in the bits of a float (or of a 4-byte integer), "rgba" holds
// 0xAARRGGBB (alpha dropped); channels are widened to 16 bits. In ascii files a float "rgb" is the
// float's value, whose bits are taken. Intensity: every type is taken as-is, rounded and clamped
// to 0..65535 (NaN becomes 0). A float intensity in 0..1 is NOT rescaled: a streaming reader cannot
// tell it from a dark 0..65535 one before it has seen every point.

#include <algorithm>
#include <array>
#include <bit>
#include <cassert>
#include <charconv>
#include <cmath>
#include <cstring>
#include <limits>
#include <optional>

#include "engine/io/byte_order.h"
#include "engine/io/file_source.h"
#include "engine/io/lzf.h"
#include "engine/io/point_reader.h"
#include "engine/io/text_numbers.h"

namespace plumb::io {
namespace {

constexpr std::uint64_t kMaxHeaderBytes = 1 << 20;
constexpr std::size_t kMaxHeaderLineBytes = 64 << 10;
constexpr std::uint64_t kMaxFieldCount = 1 << 24;  // COUNT; bounds a record's size, no overflow
// binary_compressed is decompressed into memory; a block larger than this is refused.
constexpr std::uint64_t kMaxUncompressedBytes = std::uint64_t{8} << 30;
// An LZF chunk of 3 bytes yields at most 264; a block that claims more expansion is corrupt.
constexpr std::uint64_t kMaxLzfExpansion = 88;
constexpr std::size_t kChunkBytes = std::size_t{1} << 20;  // binary records read at once

enum class DataKind { kAscii, kBinary, kCompressed };

struct Field {
  std::string name;
  char type = 'F';  // F, I or U
  std::size_t size = 4;
  std::size_t count = 1;
  std::size_t offset = 0;  // within a record
  std::size_t bytes() const { return size * count; }
};

enum Role : int { kX, kY, kZ, kColour, kIntensity, kNx, kNy, kNz, kRoleCount };

double decode(const std::byte* p, const Field& field) {
  const bool is_signed = field.type == 'I';
  switch (field.size) {
    case 1:
      return is_signed ? static_cast<double>(loadLittleEndian<std::int8_t>(p))
                       : static_cast<double>(loadLittleEndian<std::uint8_t>(p));
    case 2:
      return is_signed ? static_cast<double>(loadLittleEndian<std::int16_t>(p))
                       : static_cast<double>(loadLittleEndian<std::uint16_t>(p));
    case 4:
      if (field.type == 'F') return loadLittleEndian<float>(p);
      return is_signed ? static_cast<double>(loadLittleEndian<std::int32_t>(p))
                       : static_cast<double>(loadLittleEndian<std::uint32_t>(p));
    default:
      if (field.type == 'F') return loadLittleEndian<double>(p);
      return is_signed ? static_cast<double>(loadLittleEndian<std::int64_t>(p))
                       : static_cast<double>(loadLittleEndian<std::uint64_t>(p));
  }
}

// The packed colour of an ascii value: a float's bits, or an integer's value.
std::uint32_t packedFromText(double value, char type) {
  if (type == 'F') return std::bit_cast<std::uint32_t>(static_cast<float>(value));
  if (!std::isfinite(value) || value < -2147483648.0 || value > 4294967295.0) return 0;
  return value < 0 ? static_cast<std::uint32_t>(static_cast<std::int32_t>(value)) : static_cast<std::uint32_t>(value);
}

bool validSize(char type, std::size_t size) {
  if (type == 'F') return size == 4 || size == 8;
  return size == 1 || size == 2 || size == 4 || size == 8;
}

bool parseUnsigned(std::string_view word, std::uint64_t& value) {
  const auto [end, error] = std::from_chars(word.data(), word.data() + word.size(), value);
  return error == std::errc() && end == word.data() + word.size();
}

std::string describe(const Field& field) {
  std::string text = field.name + " (" + field.type + std::to_string(field.size);
  if (field.count > 1) text += " x" + std::to_string(field.count);
  return text + ")";
}

// One header line: its words after the keyword, and where it was.
struct HeaderLine {
  std::vector<std::string> words;
  std::uint64_t line = 0;
};

class PcdReader final : public PointReader {
 public:
  explicit PcdReader(const std::string& path) : PointReader(path), source_(path) {
    readHeader();
    layOutFields();
    if (kind_ == DataKind::kBinary) checkBinarySize();
    if (kind_ == DataKind::kCompressed) decompress();
  }

  bool read(PointBatch& batch, std::size_t max_points) override {
    assert(max_points > 0 && "read() needs room for at least one point");
    batch.clear();
    batch.points.reserve(static_cast<std::size_t>(std::min<std::uint64_t>(max_points, points_ - done_)));
    while (batch.size() < max_points && done_ < points_) {
      if (kind_ == DataKind::kAscii) readAscii(batch, max_points);
      if (kind_ == DataKind::kBinary) readBinary(batch, max_points);
      if (kind_ == DataKind::kCompressed) readCompressed(batch, max_points);
    }
    if (done_ == points_ && !checked_end_) finish();
    return !batch.points.empty();
  }

 private:
  Error lineError(std::uint64_t line, std::string_view what) const {
    return Error("'" + path_ + "' line " + std::to_string(line) + ": " + std::string(what));
  }

  // Step 1: the header lines up to DATA.
  void readHeader() {
    std::optional<HeaderLine> version, fields, sizes, types, counts, width, height, points;
    std::string line;
    std::vector<std::string_view> words;
    for (;;) {
      if (source_.offset() > kMaxHeaderBytes) {
        throw source_.errorHere("no DATA line in the first megabyte: not a PCD file");
      }
      if (!source_.readLine(line, kMaxHeaderLineBytes)) {
        throw source_.errorHere("truncated header: the file ends before the DATA line");
      }
      splitFields(line, /*comma=*/false, words);
      if (words.empty() || words[0].front() == '#') continue;
      const std::string_view key = words[0];
      HeaderLine entry{{words.begin() + 1, words.end()}, source_.lineNumber()};
      if (key == "DATA") {
        if (entry.words.size() != 1) throw source_.errorAtLine("expected 'DATA ascii|binary|binary_compressed'");
        data_line_ = entry.line;
        const std::string& kind = entry.words[0];
        if (kind == "ascii") {
          kind_ = DataKind::kAscii;
        } else if (kind == "binary") {
          kind_ = DataKind::kBinary;
        } else if (kind == "binary_compressed") {
          kind_ = DataKind::kCompressed;
        } else {
          throw source_.errorAtLine("unknown DATA kind '" + kind + "'; PCD data is ascii, binary or binary_compressed");
        }
        info_.format = "PCD " + kind;
        break;
      }
      std::optional<HeaderLine>* slot = nullptr;
      if (key == "VERSION") slot = &version;
      if (key == "FIELDS") slot = &fields;
      if (key == "SIZE") slot = &sizes;
      if (key == "TYPE") slot = &types;
      if (key == "COUNT") slot = &counts;
      if (key == "WIDTH") slot = &width;
      if (key == "HEIGHT") slot = &height;
      if (key == "POINTS") slot = &points;
      if (key == "VIEWPOINT") {
        double number = 0.0;
        if (entry.words.size() != 7 || !std::all_of(entry.words.begin(), entry.words.end(),
                                                    [&](const auto& w) { return parseNumber(w, number); })) {
          throw source_.errorAtLine("expected 'VIEWPOINT tx ty tz qw qx qy qz' (7 numbers)");
        }
        continue;
      }
      if (slot == nullptr) {
        throw source_.errorAtLine("unknown header line '" + line.substr(0, 80) +
                                  "': not a PCD file, or a header line Plumb does not know");
      }
      if (slot->has_value()) throw source_.errorAtLine("a second " + std::string(key) + " line");
      if (entry.words.empty()) throw source_.errorAtLine(std::string(key) + " has no values");
      *slot = std::move(entry);
    }

    if (version) {
      const std::string& text = version->words[0];
      if (version->words.size() != 1 || (text != "0.7" && text != ".7" && text != "0.6" && text != ".6")) {
        throw lineError(version->line, "unsupported PCD VERSION '" + text + "'; Plumb reads 0.7 and 0.6");
      }
      info_.format = "PCD " + (text.front() == '.' ? "0" + text : text) + info_.format.substr(3);
    }
    const std::array<std::pair<const std::optional<HeaderLine>*, const char*>, 5> required = {
        {{&fields, "FIELDS"}, {&sizes, "SIZE"}, {&types, "TYPE"}, {&width, "WIDTH"}, {&points, "POINTS"}}};
    for (const auto& [entry, key] : required) {
      if (!entry->has_value()) {
        throw lineError(data_line_, std::string("the header has no ") + key +
                                        " line before DATA; a PCD header needs FIELDS, SIZE, TYPE, WIDTH and POINTS");
      }
    }
    parseFields(*fields, *sizes, *types, counts);
    parseCounts(*width, height, *points);
  }

  // Step 2: FIELDS, SIZE, TYPE and COUNT (absent: all 1).
  void parseFields(const HeaderLine& names, const HeaderLine& sizes, const HeaderLine& types,
                   const std::optional<HeaderLine>& counts) {
    const std::size_t n = names.words.size();
    const auto checkLength = [&](const HeaderLine& entry, std::string_view key) {
      if (entry.words.size() != n) {
        throw lineError(entry.line, std::string(key) + " has " + std::to_string(entry.words.size()) +
                                        " values but FIELDS names " + std::to_string(n) +
                                        " fields; the lists must match one to one");
      }
    };
    checkLength(sizes, "SIZE");
    checkLength(types, "TYPE");
    if (counts) checkLength(*counts, "COUNT");
    fields_.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
      Field& field = fields_[i];
      field.name = names.words[i];
      const std::string& type = types.words[i];
      if (type != "F" && type != "I" && type != "U") {
        throw lineError(types.line, "unknown TYPE '" + type + "' for field " + field.name +
                                        "; PCD types are F (float), I (signed) and U (unsigned)");
      }
      field.type = type[0];
      std::uint64_t size = 0;
      if (!parseUnsigned(sizes.words[i], size) || !validSize(field.type, size)) {
        throw lineError(sizes.line, "invalid SIZE '" + sizes.words[i] + "' for field " + field.name + " of TYPE " +
                                        type + "; F takes 4 or 8 bytes, I and U take 1, 2, 4 or 8");
      }
      field.size = static_cast<std::size_t>(size);
      std::uint64_t count = 1;
      if (counts && (!parseUnsigned(counts->words[i], count) || count == 0 || count > kMaxFieldCount)) {
        throw lineError(counts->line, "invalid COUNT '" + counts->words[i] + "' for field " + field.name +
                                          "; expected a whole number from 1 to " + std::to_string(kMaxFieldCount));
      }
      field.count = static_cast<std::size_t>(count);
    }
  }

  void parseCounts(const HeaderLine& width, const std::optional<HeaderLine>& height, const HeaderLine& points) {
    std::uint64_t w = 0;
    std::uint64_t h = 1;
    if (width.words.size() != 1 || !parseUnsigned(width.words[0], w)) {
      throw lineError(width.line, "expected 'WIDTH <count>'");
    }
    if (height && (height->words.size() != 1 || !parseUnsigned(height->words[0], h))) {
      throw lineError(height->line, "expected 'HEIGHT <count>'");
    }
    if (points.words.size() != 1 || !parseUnsigned(points.words[0], points_)) {
      throw lineError(points.line, "expected 'POINTS <count>'");
    }
    if ((h != 0 && w > std::numeric_limits<std::uint64_t>::max() / h) || w * h != points_) {
      throw lineError(points.line, "POINTS " + std::to_string(points_) + " disagrees with WIDTH " + std::to_string(w) +
                                       " x HEIGHT " + std::to_string(h) + "; fix whichever is wrong");
    }
    info_.declared_points = points_;
  }

  // Step 3: offsets and roles.
  void layOutFields() {
    static constexpr std::pair<std::string_view, Role> kNames[] = {
        {"x", kX},         {"y", kY},         {"z", kZ},
        {"rgb", kColour},  {"rgba", kColour}, {"intensity", kIntensity},
        {"normal_x", kNx}, {"normal_y", kNy}, {"normal_z", kNz}};
    roles_.fill(-1);
    for (std::size_t i = 0; i < fields_.size(); ++i) {
      Field& field = fields_[i];
      field.offset = record_bytes_;
      record_bytes_ += field.bytes();
      total_values_ += field.count;
      int role = -1;
      for (const auto& [name, known] : kNames) {
        if (name == field.name) role = known;
      }
      if (role >= kX && role <= kZ && field.count != 1) {
        throw lineError(data_line_, "field " + field.name + " has COUNT " + std::to_string(field.count) +
                                        "; a coordinate must have COUNT 1");
      }
      // A colour is one packed 4-byte value; any other shape is kept out, and listed.
      const bool usable = field.count == 1 && (role != kColour || field.size == 4);
      if (role >= 0 && usable && roles_[static_cast<std::size_t>(role)] < 0) {
        roles_[static_cast<std::size_t>(role)] = static_cast<int>(i);
      } else if (field.name != "_") {
        info_.ignored_fields.push_back(describe(field));
      }
    }
    if (roles_[kX] < 0 || roles_[kY] < 0 || roles_[kZ] < 0) {
      throw lineError(data_line_, "the FIELDS lack x, y or z; Plumb needs point coordinates");
    }
    info_.attributes.colour = roles_[kColour] >= 0;
    info_.attributes.intensity = roles_[kIntensity] >= 0;
    info_.attributes.normals = roles_[kNx] >= 0 && roles_[kNy] >= 0 && roles_[kNz] >= 0;
    // Part of a normal is no normal: list the parts present as ignored.
    for (const Role r : {kNx, kNy, kNz}) {
      if (info_.attributes.normals || roles_[r] < 0) continue;
      info_.ignored_fields.push_back(describe(fields_[static_cast<std::size_t>(roles_[r])]));
      roles_[r] = -1;
    }
    data_start_ = source_.offset();
  }

  std::string declaredBytesText(std::uint64_t bytes) const {
    return "the header declares " + std::to_string(points_) + " points of " + std::to_string(record_bytes_) +
           " bytes (" + std::to_string(bytes) + " bytes)";
  }

  // The exact byte count of the records, or an error when it does not fit in 64 bits.
  std::uint64_t recordsBytes() const {
    if (points_ > std::numeric_limits<std::uint64_t>::max() / record_bytes_) {
      throw lineError(data_line_, "POINTS x record size overflows: the header is corrupt");
    }
    return points_ * record_bytes_;
  }

  // Step 4, binary: the file must hold exactly the declared records.
  void checkBinarySize() {
    const std::uint64_t needed = recordsBytes();
    const std::uint64_t present = source_.remaining();
    if (present < needed) {
      throw source_.errorHere("truncated: " + declaredBytesText(needed) + " but only " + std::to_string(present) +
                              " bytes follow the header, enough for " + std::to_string(present / record_bytes_) +
                              " points; the file was cut short (copy or export it again)");
    }
    if (present > needed) {
      throw source_.errorAt(data_start_ + needed, std::to_string(present - needed) +
                                                      " bytes of surplus data after the " + std::to_string(points_) +
                                                      " declared points: POINTS disagrees with the data");
    }
  }

  // Step 4, binary_compressed: check the two sizes, decompress the whole block.
  void decompress() {
    std::array<std::byte, 8> sizes{};
    source_.readExactly(sizes, "the compressed block's sizes");
    const std::uint64_t compressed = loadLittleEndian<std::uint32_t>(sizes.data());
    const std::uint64_t uncompressed = loadLittleEndian<std::uint32_t>(sizes.data() + 4);
    const std::uint64_t needed = recordsBytes();
    if (needed > kMaxUncompressedBytes) {
      throw lineError(data_line_, declaredBytesText(needed) + ", more than the " +
                                      std::to_string(kMaxUncompressedBytes >> 30) +
                                      " GiB a compressed PCD may hold in memory; save it as binary instead");
    }
    if (uncompressed != needed) {
      throw source_.errorAt(data_start_ + 4, "the compressed block holds " + std::to_string(uncompressed) +
                                                 " bytes uncompressed but " + declaredBytesText(needed) +
                                                 "; the header or the data is corrupt");
    }
    if (compressed > source_.remaining()) {
      throw source_.errorHere("truncated: the compressed block has " + std::to_string(compressed) + " bytes but only " +
                              std::to_string(source_.remaining()) + " follow; the file was cut short");
    }
    if (uncompressed > compressed * kMaxLzfExpansion) {
      throw source_.errorHere("corrupt LZF data: " + std::to_string(compressed) + " bytes cannot decompress to " +
                              std::to_string(uncompressed));
    }
    const std::uint64_t block_start = source_.offset();
    std::vector<std::byte> packed(static_cast<std::size_t>(compressed));
    source_.readExactly(packed, "the compressed block");
    checkPadding();
    data_.resize(static_cast<std::size_t>(uncompressed));
    std::size_t written = 0;
    if (!lzfDecompress(packed, data_, written) || written != data_.size()) {
      throw source_.errorAt(block_start, "corrupt LZF data: it does not decompress to the declared " +
                                             std::to_string(uncompressed) + " bytes (decoding stopped after " +
                                             std::to_string(written) + "); the file is damaged");
    }
  }

  // PCL pads the compressed files it writes with zeros (it sizes them for a memory map), so
  // zeros may follow the block; anything else is surplus data.
  void checkPadding() {
    std::array<std::byte, 4096> tail{};
    while (!source_.atEnd()) {
      const std::uint64_t start = source_.offset();
      const std::size_t got = source_.readSome(tail);
      const auto nonzero = std::find_if(tail.begin(), tail.begin() + static_cast<std::ptrdiff_t>(got),
                                        [](std::byte b) { return b != std::byte{0}; });
      if (nonzero != tail.begin() + static_cast<std::ptrdiff_t>(got)) {
        const std::uint64_t at = start + static_cast<std::uint64_t>(nonzero - tail.begin());
        throw source_.errorAt(at, "surplus data after the compressed block (" + std::to_string(source_.size() - at) +
                                      " bytes; only zero padding may follow it): the file is damaged");
      }
    }
  }

  // Step 5: one point, from its fields' bytes (`at(field)` points at a field's first value).
  template <typename At>
  void emitBinary(PointBatch& batch, At at) {
    std::array<double, kRoleCount> value{};
    for (std::size_t r = 0; r < kRoleCount; ++r) {
      if (roles_[r] >= 0 && r != kColour) {
        const auto f = static_cast<std::size_t>(roles_[r]);
        value[r] = decode(at(f), fields_[f]);
      }
    }
    const std::uint32_t packed =
        info_.attributes.colour ? loadLittleEndian<std::uint32_t>(at(static_cast<std::size_t>(roles_[kColour]))) : 0;
    emit(batch, value, packed);
  }

  void emit(PointBatch& batch, const std::array<double, kRoleCount>& value, std::uint32_t packed) {
    PointRecord point{value[kX], value[kY], value[kZ], {0, 0, 0}, 0};
    if (info_.attributes.colour) {
      point.rgb = {widenColour(static_cast<std::uint8_t>(packed >> 16)),
                   widenColour(static_cast<std::uint8_t>(packed >> 8)), widenColour(static_cast<std::uint8_t>(packed))};
    }
    if (info_.attributes.intensity) point.intensity = intensityFrom(value[kIntensity]);
    deliver(batch, point,
            {static_cast<float>(value[kNx]), static_cast<float>(value[kNy]), static_cast<float>(value[kNz])});
  }

  void readBinary(PointBatch& batch, std::size_t max_points) {
    const std::uint64_t take = std::min<std::uint64_t>(
        {max_points - batch.size(), points_ - done_, std::max<std::size_t>(1, kChunkBytes / record_bytes_)});
    chunk_.resize(static_cast<std::size_t>(take) * record_bytes_);
    source_.readExactly(chunk_, "the point records");
    for (std::size_t i = 0; i < take; ++i) {
      const std::byte* record = chunk_.data() + i * record_bytes_;
      emitBinary(batch, [&](std::size_t f) { return record + fields_[f].offset; });
    }
    done_ += take;
  }

  void readCompressed(PointBatch& batch, std::size_t max_points) {
    const std::uint64_t end = std::min<std::uint64_t>(points_, done_ + (max_points - batch.size()));
    for (std::uint64_t i = done_; i < end; ++i) {
      emitBinary(batch,
                 [&](std::size_t f) { return data_.data() + points_ * fields_[f].offset + i * fields_[f].bytes(); });
    }
    done_ = end;
  }

  void readAscii(PointBatch& batch, std::size_t max_points) {
    while (batch.size() < max_points && done_ < points_) {
      if (!source_.readLine(line_)) {
        throw source_.errorHere("truncated: the header declares " + std::to_string(points_) +
                                " points but the file ends after " + std::to_string(done_));
      }
      splitFields(line_, /*comma=*/false, words_);
      if (words_.empty()) continue;
      if (words_.size() != total_values_) {
        throw source_.errorAtLine(std::to_string(words_.size()) + " values where the header declares " +
                                  std::to_string(total_values_) + " per point (point " + std::to_string(done_ + 1) +
                                  ")");
      }
      std::array<double, kRoleCount> value{};
      std::uint32_t packed = 0;
      std::size_t column = 0;
      for (std::size_t f = 0; f < fields_.size(); ++f) {
        for (std::size_t k = 0; k < fields_[f].count; ++k, ++column) {
          double number = 0.0;
          if (!parseNumber(words_[column], number)) {
            throw source_.errorAtLine("'" + std::string(words_[column].substr(0, 40)) + "' is not a number (field " +
                                      fields_[f].name + ", point " + std::to_string(done_ + 1) + ")");
          }
          if (k > 0) continue;
          for (std::size_t r = 0; r < kRoleCount; ++r) {
            if (roles_[r] == static_cast<int>(f)) value[r] = number;
          }
          if (roles_[kColour] == static_cast<int>(f)) packed = packedFromText(number, fields_[f].type);
        }
      }
      emit(batch, value, packed);
      ++done_;
    }
  }

  // After the last point: ascii may only have blank lines left (binary was checked at open).
  void finish() {
    checked_end_ = true;
    data_ = {};
    if (kind_ != DataKind::kAscii) return;
    while (source_.readLine(line_)) {
      splitFields(line_, /*comma=*/false, words_);
      if (!words_.empty()) {
        throw source_.errorAtLine("surplus data after the " + std::to_string(points_) +
                                  " declared points: POINTS disagrees with the data");
      }
    }
  }

  FileSource source_;
  DataKind kind_ = DataKind::kAscii;
  std::vector<Field> fields_;
  std::array<int, kRoleCount> roles_{};
  std::size_t record_bytes_ = 0;
  std::size_t total_values_ = 0;  // ascii values per point
  std::uint64_t points_ = 0;
  std::uint64_t done_ = 0;  // records consumed, delivered or skipped
  std::uint64_t data_line_ = 0;
  std::uint64_t data_start_ = 0;
  bool checked_end_ = false;
  std::vector<std::byte> chunk_;  // binary records being decoded
  std::vector<std::byte> data_;   // binary_compressed: the whole decompressed block
  std::string line_;
  std::vector<std::string_view> words_;
};

}  // namespace

std::unique_ptr<PointReader> openPcd(const std::string& path) {
  return std::make_unique<PcdReader>(path);
}

}  // namespace plumb::io
