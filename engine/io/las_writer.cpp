#include "engine/io/las_writer.h"

#include <cmath>
#include <cstring>
#include <limits>

#include "engine/core/error.h"
#include "engine/io/byte_order.h"

namespace plumb::io {
namespace {

// LAS 1.2, table 4: the public header block is 227 bytes; no VLRs follow, so the points start
// right after it.
constexpr std::size_t kHeaderBytes = 227;
constexpr std::size_t kCountOffset = 107;     // number of point records, u32
constexpr std::size_t kByReturnOffset = 111;  // number of points by return, 5 x u32
constexpr std::size_t kBoundsOffset = 179;    // max x, min x, max y, min y, max z, min z
constexpr std::size_t kBufferPoints = 1 << 16;

void putText(std::byte* out, const std::string& text, std::size_t field) {
  std::memcpy(out, text.data(), std::min(text.size(), field));
}

}  // namespace

LasWriter::LasWriter(std::string path, const LasWriterOptions& options) : file_(std::move(path)), options_(options) {
  if (!(options.scale > 0.0) || !std::isfinite(options.scale))
    throw fileError(file_.path(), "a LAS scale must be positive");
  std::array<std::byte, kHeaderBytes> header{};
  std::byte* out = header.data();
  std::memcpy(out, "LASF", 4);
  out[24] = std::byte{1};  // version 1.2
  out[25] = std::byte{2};
  putText(out + 26, "plumb simulate", 32);  // system identifier
  putText(out + 58, options.software, 32);  // generating software
  packLittleEndian(out + 94, static_cast<std::uint16_t>(kHeaderBytes));
  packLittleEndian(out + 96, static_cast<std::uint32_t>(kHeaderBytes));  // offset to the point data
  packLittleEndian(out + 100, std::uint32_t{0});                         // variable length records
  out[104] = std::byte{2};                                               // point data format
  packLittleEndian(out + 105, static_cast<std::uint16_t>(kRecordBytes));
  std::byte* at = out + 131;
  for (int a = 0; a < 3; ++a) at = packLittleEndian(at, options.scale);
  for (double offset : options.offset) at = packLittleEndian(at, offset);
  file_.write(header.data(), header.size());
  buffer_.reserve(kBufferPoints * kRecordBytes);
  min_.fill(std::numeric_limits<double>::infinity());
  max_.fill(-std::numeric_limits<double>::infinity());
}

void LasWriter::add(const std::array<double, 3>& position, std::uint16_t intensity,
                    const std::array<std::uint16_t, 3>& rgb, std::uint16_t source_id) {
  if (count_ == kMaxPoints) {
    throw fileError(file_.path(), "LAS 1.2 holds at most 4,294,967,295 points");
  }
  std::array<std::int32_t, 3> integer{};
  for (std::size_t a = 0; a < 3; ++a) {
    const double steps = std::round((position[a] - options_.offset[a]) / options_.scale);
    if (!(std::abs(steps) <= double{std::numeric_limits<std::int32_t>::max()})) {
      throw fileError(file_.path(), "point " + std::to_string(count_) +
                                        " lies beyond the reach of LAS's 32-bit "
                                        "coordinates around the offset (choose another offset or scale)");
    }
    integer[a] = static_cast<std::int32_t>(steps);
    // The bounds of the stored coordinates, as readers will decode them.
    const double stored = integer[a] * options_.scale + options_.offset[a];
    min_[a] = std::min(min_[a], stored);
    max_[a] = std::max(max_[a], stored);
  }
  const std::size_t size = buffer_.size();
  buffer_.resize(size + kRecordBytes);
  std::byte* out = buffer_.data() + size;
  for (std::int32_t v : integer) out = packLittleEndian(out, v);
  out = packLittleEndian(out, intensity);
  out = packLittleEndian(out, std::uint8_t{0b0000'1001});  // return 1 of 1
  out = packLittleEndian(out, std::uint8_t{0});            // classification: never classified
  out = packLittleEndian(out, std::int8_t{0});             // scan angle rank
  out = packLittleEndian(out, std::uint8_t{0});            // user data
  out = packLittleEndian(out, source_id);
  for (std::uint16_t channel : rgb) out = packLittleEndian(out, channel);
  ++count_;
  if (buffer_.size() >= kBufferPoints * kRecordBytes) flush();
}

void LasWriter::flush() {
  file_.write(buffer_.data(), buffer_.size());
  buffer_.clear();
}

void LasWriter::finish() {
  flush();
  std::array<std::byte, 4> count{};
  packLittleEndian(count.data(), static_cast<std::uint32_t>(count_));
  file_.overwrite(kCountOffset, count);
  file_.overwrite(kByReturnOffset, count);  // every point is its pulse's first and only return
  if (count_ > 0) {
    std::array<std::byte, 48> bounds{};
    std::byte* at = bounds.data();
    for (std::size_t a = 0; a < 3; ++a) {
      at = packLittleEndian(at, max_[a]);
      at = packLittleEndian(at, min_[a]);
    }
    file_.overwrite(kBoundsOffset, bounds);
  }
  file_.finish();
}

void LasWriter::commit() {
  file_.commit();
}

}  // namespace plumb::io
