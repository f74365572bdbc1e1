// LASzip point-wise coder, items POINT10, GPSTIME11, RGB12 and BYTE, version 2 (LASzip 2.0 and
// later, compressor 2), after the LASzip reference implementation,
// src/lasreaditemcompressed_v2.cpp and src/laszip_common_v2.hpp (read, not copied); Isenburg
// 2013, "LASzip: lossless compression of LiDAR data", PE&RS 79(2).
//
// POINT10 v2, per point:
//   1. A symbol of 6 bits says which fields other than x y z changed: the return byte (32; a
//      symbol, its model chosen by the previous byte), intensity (16), classification (8; as the
//      return byte), scan angle rank (4; a symbol added to the previous value, its model chosen by
//      the scan direction flag), user data (2; as the return byte), point source id (1).
//   2. The return number r and number of returns n pick a context m (0 to 15, a table that also
//      gives distinct contexts to files numbering returns from 0 or mixing r and n up) and a
//      level l (0 to 7, how many returns from the last). Intensity is predicted by the last
//      intensity of the same m (context min(m, 3)); unchanged, it is that last intensity.
//   3. x: the previous x plus a difference predicted by the streaming median of the last five x
//      differences of the same m (context: n = 1). y likewise, its context also from the k of x
//      (even, at most 20). z: predicted by the last z of the same level l, its context from the
//      mean k of x and y (even, at most 18).
// GPSTIME11 v2: up to four interleaved time sequences (files merged from several flight lines),
//   each with its last time and last integer difference. A zero difference is followed by a
//   symbol: unchanged, a 32-bit difference, a jump (the high 32 bits predicted by the last time's,
//   the low 32 raw) or a switch to another sequence. Otherwise a multiplier symbol: the previous
//   difference times -10 to 500 predicts the next (0: no prediction), or unchanged, a jump, or a
//   switch. Unusual differences become the new prediction after four in a row.
// RGB12 v2: a symbol says which colour bytes changed and whether the colour is grey (red = green
//   = blue). Red's bytes are coded as corrections of the previous ones; green's and blue's are
//   predicted from the previous value plus red's change (blue: the mean of red's and green's),
//   clamped to 0..255, and corrected.
// BYTE v2: each extra byte is the previous one plus a symbol (mod 256), one model per byte.
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
#include "engine/io/laz_streaming_median.h"

namespace plumb::io {
namespace {

// POINT10's byte offsets.
constexpr std::size_t kXAt = 0, kYAt = 4, kZAt = 8, kIntensityAt = 12, kReturnByteAt = 14;
constexpr std::size_t kClassificationAt = 15, kScanAngleAt = 16, kUserDataAt = 17, kSourceIdAt = 18;
constexpr std::size_t kPoint10Bytes = 20;

// Context m, indexed [number of returns n][return number r]: the regular pairs (1 <= r <= n <= 5)
// take contexts 0 to 14 in order; irregular ones (counted from 0, r > n, n > 5) reuse nearby ones.
constexpr std::array<std::array<std::uint8_t, 8>, 8> kReturnContext{{
    {15, 14, 13, 12, 11, 10, 9, 8},
    {14, 0, 1, 3, 6, 10, 10, 9},
    {13, 1, 2, 4, 7, 11, 11, 10},
    {12, 3, 4, 5, 8, 12, 12, 11},
    {11, 6, 7, 8, 9, 13, 13, 12},
    {10, 10, 11, 12, 13, 14, 14, 13},
    {9, 10, 11, 12, 13, 14, 15, 14},
    {8, 9, 10, 11, 12, 13, 14, 15},
}};

// Level l of [n][r]: |n - r|, how far the return is from the last one.
constexpr std::uint8_t returnLevel(unsigned n, unsigned r) {
  return static_cast<std::uint8_t>(n > r ? n - r : r - n);
}

std::int32_t wrappingAdd(std::int32_t a, std::int32_t b) {
  return static_cast<std::int32_t>(static_cast<std::uint32_t>(a) + static_cast<std::uint32_t>(b));
}

std::uint8_t clampToByte(int value) {
  return static_cast<std::uint8_t>(std::clamp(value, 0, 255));
}

class Point10V2 final : public LazItemDecoder {
 public:
  void start(const std::byte* first) override {
    for (StreamingMedian5& median : x_medians_) median.reset();
    for (StreamingMedian5& median : y_medians_) median.reset();
    last_intensity_ = {};
    last_height_ = {};
    changed_.reset();
    intensity_.reset();
    for (LazSymbolModel& model : scan_angle_) model.reset();
    source_id_.reset();
    return_byte_.reset();
    classification_.reset();
    user_data_.reset();
    dx_.reset();
    dy_.reset();
    z_.reset();
    std::memcpy(last_.data(), first, kPoint10Bytes);
    // The next points' intensity starts from 0, not from the first point's (as the encoder's): it is
    // predicted by the last intensity of each return context, all 0 at a chunk's start.
    last_[kIntensityAt] = last_[kIntensityAt + 1] = std::byte{0};
  }

  void decode(LazArithmeticDecoder& decoder, std::byte* out) override {
    const std::uint32_t changed = decoder.decodeSymbol(changed_);
    if (changed & 32) last_[kReturnByteAt] = decodeByte(decoder, return_byte_, kReturnByteAt);
    const unsigned r = byteAt(kReturnByteAt) & 7u;
    const unsigned n = (byteAt(kReturnByteAt) >> 3) & 7u;
    const std::uint8_t m = kReturnContext[n][r];
    const std::uint8_t l = returnLevel(n, r);
    if (changed != 0) {
      if (changed & 16) {
        last_intensity_[m] =
            static_cast<std::uint16_t>(intensity_.decompress(decoder, last_intensity_[m], std::min<unsigned>(m, 3)));
      }
      packLittleEndian(last_.data() + kIntensityAt, last_intensity_[m]);
      if (changed & 8) last_[kClassificationAt] = decodeByte(decoder, classification_, kClassificationAt);
      if (changed & 4) {
        const std::uint32_t scan_direction = (byteAt(kReturnByteAt) >> 6) & 1u;
        const std::uint32_t step = decoder.decodeSymbol(scan_angle_[scan_direction]);
        last_[kScanAngleAt] = static_cast<std::byte>(static_cast<std::uint8_t>(step + byteAt(kScanAngleAt)));
      }
      if (changed & 2) last_[kUserDataAt] = decodeByte(decoder, user_data_, kUserDataAt);
      if (changed & 1) {
        const auto previous = loadLittleEndian<std::uint16_t>(last_.data() + kSourceIdAt);
        packLittleEndian(last_.data() + kSourceIdAt,
                         static_cast<std::uint16_t>(source_id_.decompress(decoder, previous, 0)));
      }
    }

    const unsigned single_return = n == 1 ? 1 : 0;
    const std::int32_t x_diff = dx_.decompress(decoder, x_medians_[m].median(), single_return);
    packLittleEndian(last_.data() + kXAt, wrappingAdd(loadLittleEndian<std::int32_t>(last_.data() + kXAt), x_diff));
    x_medians_[m].add(x_diff);

    unsigned k = dx_.k();
    const std::int32_t y_diff =
        dy_.decompress(decoder, y_medians_[m].median(), single_return + (k < 20 ? k & ~1u : 20u));
    packLittleEndian(last_.data() + kYAt, wrappingAdd(loadLittleEndian<std::int32_t>(last_.data() + kYAt), y_diff));
    y_medians_[m].add(y_diff);

    k = (dx_.k() + dy_.k()) / 2;
    last_height_[l] = z_.decompress(decoder, last_height_[l], single_return + (k < 18 ? k & ~1u : 18u));
    packLittleEndian(last_.data() + kZAt, last_height_[l]);

    std::memcpy(out, last_.data(), kPoint10Bytes);
  }

 private:
  std::uint8_t byteAt(std::size_t at) const { return std::to_integer<std::uint8_t>(last_[at]); }

  std::byte decodeByte(LazArithmeticDecoder& decoder, LazModelsByPreviousByte& models, std::size_t at) {
    return static_cast<std::byte>(decoder.decodeSymbol(models[byteAt(at)]));
  }

  std::array<std::byte, kPoint10Bytes> last_{};
  std::array<std::uint16_t, 16> last_intensity_{};
  std::array<StreamingMedian5, 16> x_medians_, y_medians_;
  std::array<std::int32_t, 8> last_height_{};

  LazSymbolModel changed_{64};
  LazIntegerDecompressor intensity_{16, 4};
  std::array<LazSymbolModel, 2> scan_angle_{LazSymbolModel(256), LazSymbolModel(256)};
  LazIntegerDecompressor source_id_{16, 1};
  LazModelsByPreviousByte return_byte_, classification_, user_data_;
  LazIntegerDecompressor dx_{32, 2};
  LazIntegerDecompressor dy_{32, 22};
  LazIntegerDecompressor z_{32, 20};
};

class GpsTime11V2 final : public LazItemDecoder {
 public:
  void start(const std::byte* first) override {
    current_ = newest_ = 0;
    last_time_ = {};
    last_diff_ = {};
    extreme_count_ = {};
    multiplier_.reset();
    after_zero_.reset();
    diff_.reset();
    last_time_[0] = loadLittleEndian<std::uint64_t>(first);
  }

  void decode(LazArithmeticDecoder& decoder, std::byte* out) override {
    // A switch of sequence is followed by the coding of the point's time in the new one; the
    // loop stands for the reference's recursion (a corrupt stream cannot exhaust the stack).
    for (;;) {
      if (last_diff_[current_] == 0) {
        const std::uint32_t code = decoder.decodeSymbol(after_zero_);
        if (code == 1) {  // a difference of 32 bits
          last_diff_[current_] = diff_.decompress(decoder, 0, 0);
          addToTime(last_diff_[current_]);
          extreme_count_[current_] = 0;
        } else if (code == 2) {
          jump(decoder);
        } else if (code > 2) {
          current_ = (current_ + code - 2) & 3u;
          continue;
        }  // 0: unchanged
        break;
      }
      const std::uint32_t code = decoder.decodeSymbol(multiplier_);
      if (code == 1) {
        addToTime(diff_.decompress(decoder, last_diff_[current_], 1));
        extreme_count_[current_] = 0;
      } else if (code < kUnchanged) {
        std::int32_t diff = 0;
        if (code == 0) {
          diff = diff_.decompress(decoder, 0, 7);
          adoptAfterRepeats(diff);
        } else if (code < kMaxMultiplier) {
          diff = diff_.decompress(decoder, scaled(static_cast<std::int32_t>(code), last_diff_[current_]),
                                  code < 10 ? 2 : 3);
        } else if (code == kMaxMultiplier) {
          diff = diff_.decompress(decoder, scaled(kMaxMultiplier, last_diff_[current_]), 4);
          adoptAfterRepeats(diff);
        } else {
          // Codes above 500 stand for the negative multipliers -1 to -10.
          const std::int32_t multiplier = static_cast<std::int32_t>(kMaxMultiplier) - static_cast<std::int32_t>(code);
          if (multiplier > kMinMultiplier) {
            diff = diff_.decompress(decoder, scaled(multiplier, last_diff_[current_]), 5);
          } else {
            diff = diff_.decompress(decoder, scaled(kMinMultiplier, last_diff_[current_]), 6);
            adoptAfterRepeats(diff);
          }
        }
        addToTime(diff);
      } else if (code == kJump) {
        jump(decoder);
      } else if (code > kJump) {
        current_ = (current_ + code - kJump) & 3u;
        continue;
      }  // kUnchanged
      break;
    }
    packLittleEndian(out, last_time_[current_]);
  }

 private:
  static constexpr std::int32_t kMaxMultiplier = 500;
  static constexpr std::int32_t kMinMultiplier = -10;
  static constexpr std::uint32_t kUnchanged = kMaxMultiplier - kMinMultiplier + 1;  // 511
  static constexpr std::uint32_t kJump = kMaxMultiplier - kMinMultiplier + 2;       // 512
  static constexpr std::uint32_t kCodes = kMaxMultiplier - kMinMultiplier + 6;      // 516: 3 switches

  static std::int32_t scaled(std::int32_t multiplier, std::int32_t diff) {
    return static_cast<std::int32_t>(static_cast<std::uint32_t>(multiplier) * static_cast<std::uint32_t>(diff));
  }

  void addToTime(std::int32_t diff) {
    last_time_[current_] += static_cast<std::uint64_t>(static_cast<std::int64_t>(diff));
  }

  // A new sequence: the high 32 bits predicted by the current time's, the low 32 bits raw.
  void jump(LazArithmeticDecoder& decoder) {
    newest_ = (newest_ + 1) & 3u;
    const auto high_prediction = static_cast<std::int32_t>(static_cast<std::uint32_t>(last_time_[current_] >> 32));
    const auto high = static_cast<std::uint32_t>(diff_.decompress(decoder, high_prediction, 8));
    last_time_[newest_] = (std::uint64_t{high} << 32) | decoder.readInt();
    current_ = newest_;
    last_diff_[current_] = 0;
    extreme_count_[current_] = 0;
  }

  // An unusual difference becomes the new prediction only once it has come four times running.
  void adoptAfterRepeats(std::int32_t diff) {
    if (++extreme_count_[current_] > 3) {
      last_diff_[current_] = diff;
      extreme_count_[current_] = 0;
    }
  }

  std::uint32_t current_ = 0, newest_ = 0;
  std::array<std::uint64_t, 4> last_time_{};  // the doubles' bits, as integers
  std::array<std::int32_t, 4> last_diff_{};
  std::array<int, 4> extreme_count_{};
  LazSymbolModel multiplier_{kCodes};
  LazSymbolModel after_zero_{6};
  LazIntegerDecompressor diff_{32, 9};
};

class Rgb12V2 final : public LazItemDecoder {
 public:
  void start(const std::byte* first) override {
    changed_.reset();
    for (LazSymbolModel& model : corrections_) model.reset();
    for (std::size_t c = 0; c < 3; ++c) last_[c] = loadLittleEndian<std::uint16_t>(first + 2 * c);
  }

  void decode(LazArithmeticDecoder& decoder, std::byte* out) override {
    const std::uint32_t changed = decoder.decodeSymbol(changed_);
    std::array<std::uint16_t, 3> colour{};
    // Red: each byte its previous value plus a correction (mod 256).
    const int red_low = corrected(decoder, changed, 0, lowByte(last_[0]));
    const int red_high = corrected(decoder, changed, 1, highByte(last_[0]));
    colour[0] = static_cast<std::uint16_t>(red_low | (red_high << 8));
    if (changed & (1u << 6)) {
      // Green and blue follow red's change; blue the mean of red's and green's.
      int step = red_low - lowByte(last_[0]);
      const int green_low = predicted(decoder, changed, 2, step, lowByte(last_[1]));
      int blue_low = lowByte(last_[2]);
      if (changed & (1u << 4)) {
        step = (step + (green_low - lowByte(last_[1]))) / 2;
        blue_low = predicted(decoder, changed, 4, step, lowByte(last_[2]));
      }
      step = red_high - highByte(last_[0]);
      const int green_high = predicted(decoder, changed, 3, step, highByte(last_[1]));
      int blue_high = highByte(last_[2]);
      if (changed & (1u << 5)) {
        step = (step + (green_high - highByte(last_[1]))) / 2;
        blue_high = predicted(decoder, changed, 5, step, highByte(last_[2]));
      }
      colour[1] = static_cast<std::uint16_t>(green_low | (green_high << 8));
      colour[2] = static_cast<std::uint16_t>(blue_low | (blue_high << 8));
    } else {
      colour[1] = colour[2] = colour[0];  // grey
    }
    for (std::size_t c = 0; c < 3; ++c) packLittleEndian(out + 2 * c, colour[c]);
    last_ = colour;
  }

 private:
  static int lowByte(std::uint16_t value) { return value & 0xFF; }
  static int highByte(std::uint16_t value) { return value >> 8; }

  // Byte `index` (0 red low, 1 red high, 2 green low, 3 green high, 4 blue low, 5 blue high):
  // `previous` plus its decoded correction when the byte changed, else `previous`.
  int corrected(LazArithmeticDecoder& decoder, std::uint32_t changed, unsigned index, int previous) {
    if ((changed & (1u << index)) == 0) return previous;
    return static_cast<std::uint8_t>(static_cast<int>(decoder.decodeSymbol(corrections_[index])) + previous);
  }

  // Green's and blue's bytes: `previous` plus red's `step`, clamped, plus the correction.
  int predicted(LazArithmeticDecoder& decoder, std::uint32_t changed, unsigned index, int step, int previous) {
    if ((changed & (1u << index)) == 0) return previous;
    return static_cast<std::uint8_t>(static_cast<int>(decoder.decodeSymbol(corrections_[index])) +
                                     clampToByte(step + previous));
  }

  std::array<std::uint16_t, 3> last_{};
  LazSymbolModel changed_{128};
  std::array<LazSymbolModel, 6> corrections_{LazSymbolModel(256), LazSymbolModel(256), LazSymbolModel(256),
                                             LazSymbolModel(256), LazSymbolModel(256), LazSymbolModel(256)};
};

class ByteV2 final : public LazItemDecoder {
 public:
  explicit ByteV2(std::size_t count) : last_(count) {
    models_.reserve(count);
    for (std::size_t i = 0; i < count; ++i) models_.emplace_back(256);
  }

  void start(const std::byte* first) override {
    for (LazSymbolModel& model : models_) model.reset();
    std::memcpy(last_.data(), first, last_.size());
  }

  void decode(LazArithmeticDecoder& decoder, std::byte* out) override {
    for (std::size_t i = 0; i < last_.size(); ++i) {
      last_[i] = static_cast<std::uint8_t>(last_[i] + decoder.decodeSymbol(models_[i]));
    }
    std::memcpy(out, last_.data(), last_.size());
  }

 private:
  std::vector<std::uint8_t> last_;
  std::vector<LazSymbolModel> models_;
};

}  // namespace

std::unique_ptr<LazItemDecoder> makeLazItemDecoderV2(const LazItem& item) {
  switch (static_cast<LazItemType>(item.type)) {
    case LazItemType::kPoint10:
      return item.size == kPoint10Bytes ? std::make_unique<Point10V2>() : nullptr;
    case LazItemType::kGpsTime11:
      return item.size == 8 ? std::make_unique<GpsTime11V2>() : nullptr;
    case LazItemType::kRgb12:
      return item.size == 6 ? std::make_unique<Rgb12V2>() : nullptr;
    case LazItemType::kByte:
      return item.size >= 1 ? std::make_unique<ByteV2>(item.size) : nullptr;
    default:
      return nullptr;
  }
}

}  // namespace plumb::io
