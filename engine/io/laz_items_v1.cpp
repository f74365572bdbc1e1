// LASzip point-wise coder, items POINT10, GPSTIME11, RGB12 and BYTE, version 1 (LASzip 1.x,
// compressor 1), after the LASzip reference implementation, src/lasreaditemcompressed_v1.cpp
// (read, not copied); Isenburg 2013, "LASzip: lossless compression of LiDAR data", PE&RS 79(2).
//
// POINT10 v1, per point:
//   1. x: the previous x plus a difference predicted by the median of the last three x
//      differences (one context). y likewise, its context the k of x (at most 19). z: predicted
//      by the previous z, its context the mean k of x and y (at most 19).
//   2. A symbol of 6 bits says which other fields changed: intensity (32, predicted by the
//      previous intensity), the return byte (16) and classification (8) and user data (2) (each
//      a symbol whose model is chosen by the previous value of the byte), scan angle rank (4,
//      predicted by the previous one, context: the mean k above below 3) and point source id (1).
// GPSTIME11 v1: the time as a 64-bit integer; the previous integer difference predicts the next,
//   scaled by a decoded multiplier (0 to 509: a fraction 1/4, the same, or 2 to 509 times it),
//   or the time is unchanged (511) or stored whole (510; or 2 after a zero difference).
// RGB12 v1: a symbol says which of the six colour bytes changed; each changed one is predicted
//   by its previous value (8 bits, one context per byte).
// BYTE v1: every extra byte predicted by its previous value (8 bits, one context per byte).
//
// Arithmetic on coordinates and times wraps around in 32 and 64 bits as the reference's does:
// corrupt input gives wrong values, never undefined behaviour.

#include <algorithm>
#include <array>
#include <cstring>
#include <vector>

#include "engine/io/byte_order.h"
#include "engine/io/laz_integer_decompressor.h"
#include "engine/io/laz_items.h"

namespace plumb::io {
namespace {

// POINT10's byte offsets.
constexpr std::size_t kXAt = 0, kYAt = 4, kZAt = 8, kIntensityAt = 12, kReturnByteAt = 14;
constexpr std::size_t kClassificationAt = 15, kScanAngleAt = 16, kUserDataAt = 17, kSourceIdAt = 18;
constexpr std::size_t kPoint10Bytes = 20;

std::uint8_t byteAt(const std::array<std::byte, kPoint10Bytes>& point, std::size_t at) {
  return std::to_integer<std::uint8_t>(point[at]);
}

std::int32_t median3(std::int32_t a, std::int32_t b, std::int32_t c) {
  return std::max(std::min(a, b), std::min(std::max(a, b), c));
}

std::int32_t wrappingAdd(std::int32_t a, std::int32_t b) {
  return static_cast<std::int32_t>(static_cast<std::uint32_t>(a) + static_cast<std::uint32_t>(b));
}

class Point10V1 final : public LazItemDecoder {
 public:
  void start(const std::byte* first) override {
    x_diffs_ = {};
    y_diffs_ = {};
    next_diff_ = 0;
    dx_.reset();
    dy_.reset();
    z_.reset();
    intensity_.reset();
    scan_angle_.reset();
    source_id_.reset();
    changed_.reset();
    return_byte_.reset();
    classification_.reset();
    user_data_.reset();
    std::memcpy(last_.data(), first, kPoint10Bytes);
  }

  void decode(LazArithmeticDecoder& decoder, std::byte* out) override {
    std::array<std::byte, kPoint10Bytes> point = last_;

    const std::int32_t x_diff = dx_.decompress(decoder, median3(x_diffs_[0], x_diffs_[1], x_diffs_[2]), 0);
    packLittleEndian(point.data() + kXAt, wrappingAdd(loadLittleEndian<std::int32_t>(last_.data() + kXAt), x_diff));
    unsigned k = dx_.k();
    const std::int32_t y_diff =
        dy_.decompress(decoder, median3(y_diffs_[0], y_diffs_[1], y_diffs_[2]), std::min(k, 19u));
    packLittleEndian(point.data() + kYAt, wrappingAdd(loadLittleEndian<std::int32_t>(last_.data() + kYAt), y_diff));
    k = (k + dy_.k()) / 2;
    packLittleEndian(point.data() + kZAt,
                     z_.decompress(decoder, loadLittleEndian<std::int32_t>(last_.data() + kZAt), std::min(k, 19u)));

    const std::uint32_t changed = decoder.decodeSymbol(changed_);
    if (changed & 32) {
      const auto previous = loadLittleEndian<std::uint16_t>(last_.data() + kIntensityAt);
      packLittleEndian(point.data() + kIntensityAt,
                       static_cast<std::uint16_t>(intensity_.decompress(decoder, previous, 0)));
    }
    if (changed & 16) point[kReturnByteAt] = decodeByte(decoder, return_byte_, kReturnByteAt);
    if (changed & 8) point[kClassificationAt] = decodeByte(decoder, classification_, kClassificationAt);
    if (changed & 4) {
      const std::int32_t angle = scan_angle_.decompress(decoder, byteAt(last_, kScanAngleAt), k < 3 ? 1 : 0);
      point[kScanAngleAt] = static_cast<std::byte>(static_cast<std::uint8_t>(angle));
    }
    if (changed & 2) point[kUserDataAt] = decodeByte(decoder, user_data_, kUserDataAt);
    if (changed & 1) {
      const auto previous = loadLittleEndian<std::uint16_t>(last_.data() + kSourceIdAt);
      packLittleEndian(point.data() + kSourceIdAt,
                       static_cast<std::uint16_t>(source_id_.decompress(decoder, previous, 0)));
    }

    x_diffs_[next_diff_] = x_diff;
    y_diffs_[next_diff_] = y_diff;
    next_diff_ = (next_diff_ + 1) % 3;
    last_ = point;
    std::memcpy(out, point.data(), kPoint10Bytes);
  }

 private:
  std::byte decodeByte(LazArithmeticDecoder& decoder, LazModelsByPreviousByte& models, std::size_t at) {
    return static_cast<std::byte>(decoder.decodeSymbol(models[byteAt(last_, at)]));
  }

  std::array<std::byte, kPoint10Bytes> last_{};
  std::array<std::int32_t, 3> x_diffs_{}, y_diffs_{};
  std::size_t next_diff_ = 0;

  LazIntegerDecompressor dx_{32, 1};
  LazIntegerDecompressor dy_{32, 20};
  LazIntegerDecompressor z_{32, 20};
  LazIntegerDecompressor intensity_{16, 1};
  LazIntegerDecompressor scan_angle_{8, 2};
  LazIntegerDecompressor source_id_{16, 1};
  LazSymbolModel changed_{64};
  LazModelsByPreviousByte return_byte_, classification_, user_data_;
};

class GpsTime11V1 final : public LazItemDecoder {
 public:
  void start(const std::byte* first) override {
    last_diff_ = 0;
    extreme_count_ = 0;
    multiplier_.reset();
    after_zero_.reset();
    diff_.reset();
    last_time_ = loadLittleEndian<std::uint64_t>(first);
  }

  void decode(LazArithmeticDecoder& decoder, std::byte* out) override {
    if (last_diff_ == 0) {
      const std::uint32_t code = decoder.decodeSymbol(after_zero_);
      if (code == 1) {  // a difference of 32 bits
        last_diff_ = diff_.decompress(decoder, 0, 0);
        addToTime(last_diff_);
      } else if (code == 2) {  // a jump: the whole time
        last_time_ = decoder.readInt64();
      }  // 0: unchanged
    } else {
      const std::uint32_t multiplier = decoder.decodeSymbol(multiplier_);
      if (multiplier < kWholeTime) {
        std::int32_t diff = 0;
        if (multiplier == 1) {
          diff = diff_.decompress(decoder, last_diff_, 1);
          last_diff_ = diff;
          extreme_count_ = 0;
        } else if (multiplier == 0) {
          diff = diff_.decompress(decoder, last_diff_ / 4, 2);
          adoptAfterRepeats(diff);
        } else {
          const std::int32_t prediction = scaled(multiplier, last_diff_);
          const unsigned context = multiplier < 10 ? 3 : multiplier < 50 ? 4 : 5;
          diff = diff_.decompress(decoder, prediction, context);
          if (multiplier == kWholeTime - 1) adoptAfterRepeats(diff);
        }
        addToTime(diff);
      } else if (multiplier == kWholeTime) {
        last_time_ = decoder.readInt64();
      }  // kWholeTime + 1: unchanged
    }
    packLittleEndian(out, last_time_);
  }

 private:
  static constexpr std::uint32_t kMultipliers = 512;
  static constexpr std::uint32_t kWholeTime = kMultipliers - 2;

  static std::int32_t scaled(std::uint32_t multiplier, std::int32_t diff) {
    return static_cast<std::int32_t>(multiplier * static_cast<std::uint32_t>(diff));
  }

  void addToTime(std::int32_t diff) { last_time_ += static_cast<std::uint64_t>(static_cast<std::int64_t>(diff)); }

  // An unusual difference becomes the new prediction only once it has come four times running.
  void adoptAfterRepeats(std::int32_t diff) {
    if (++extreme_count_ > 3) {
      last_diff_ = diff;
      extreme_count_ = 0;
    }
  }

  std::uint64_t last_time_ = 0;  // the double's bits, as an integer
  std::int32_t last_diff_ = 0;
  int extreme_count_ = 0;
  LazSymbolModel multiplier_{kMultipliers};
  LazSymbolModel after_zero_{3};
  LazIntegerDecompressor diff_{32, 6};
};

class Rgb12V1 final : public LazItemDecoder {
 public:
  void start(const std::byte* first) override {
    changed_.reset();
    colour_.reset();
    for (std::size_t c = 0; c < 3; ++c) last_[c] = loadLittleEndian<std::uint16_t>(first + 2 * c);
  }

  void decode(LazArithmeticDecoder& decoder, std::byte* out) override {
    const std::uint32_t changed = decoder.decodeSymbol(changed_);
    for (unsigned c = 0; c < 3; ++c) {
      const std::uint16_t previous = last_[c];
      auto value = static_cast<std::uint16_t>(previous & 0x00FF);
      if (changed & (1u << (2 * c)))
        value = static_cast<std::uint16_t>(colour_.decompress(decoder, previous & 0xFF, 2 * c));
      if (changed & (1u << (2 * c + 1))) {
        const auto high = static_cast<std::uint16_t>(colour_.decompress(decoder, previous >> 8, 2 * c + 1));
        value = static_cast<std::uint16_t>(value | (high << 8));
      } else {
        value = static_cast<std::uint16_t>(value | (previous & 0xFF00));
      }
      last_[c] = value;
      packLittleEndian(out + 2 * c, value);
    }
  }

 private:
  std::array<std::uint16_t, 3> last_{};
  LazSymbolModel changed_{64};
  LazIntegerDecompressor colour_{8, 6};
};

class ByteV1 final : public LazItemDecoder {
 public:
  explicit ByteV1(std::size_t count) : last_(count), bytes_(8, static_cast<unsigned>(count)) {}

  void start(const std::byte* first) override {
    bytes_.reset();
    std::memcpy(last_.data(), first, last_.size());
  }

  void decode(LazArithmeticDecoder& decoder, std::byte* out) override {
    for (std::size_t i = 0; i < last_.size(); ++i) {
      const std::int32_t value = bytes_.decompress(decoder, last_[i], static_cast<unsigned>(i));
      last_[i] = static_cast<std::uint8_t>(value);
    }
    std::memcpy(out, last_.data(), last_.size());
  }

 private:
  std::vector<std::uint8_t> last_;
  LazIntegerDecompressor bytes_;
};

}  // namespace

std::unique_ptr<LazItemDecoder> makeLazItemDecoderV1(const LazItem& item) {
  switch (static_cast<LazItemType>(item.type)) {
    case LazItemType::kPoint10:
      return item.size == kPoint10Bytes ? std::make_unique<Point10V1>() : nullptr;
    case LazItemType::kGpsTime11:
      return item.size == 8 ? std::make_unique<GpsTime11V1>() : nullptr;
    case LazItemType::kRgb12:
      return item.size == 6 ? std::make_unique<Rgb12V1>() : nullptr;
    case LazItemType::kByte:
      return item.size >= 1 ? std::make_unique<ByteV1>(item.size) : nullptr;
    default:
      return nullptr;
  }
}

}  // namespace plumb::io
