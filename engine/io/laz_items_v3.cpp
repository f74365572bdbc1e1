// LASzip layered coder (compressor 3), items POINT14, RGB14, RGBNIR14 and BYTE14, versions 3 and
// 4, after the LASzip reference implementation, src/lasreaditemcompressed_v3.cpp,
// src/lasreaditemcompressed_v4.cpp and src/laszip_common_v3.hpp (read, not copied); Isenburg
// 2013, "LASzip: lossless compression of LiDAR data", PE&RS 79(2).
//
// POINT14 (30 bytes, LAS 1.4 point formats 6 to 10), nine layers: x/y with the returns and the
// scanner channel, z, classification, flags, intensity, scan angle, user data, point source, GPS
// time. Per point:
//   1. In the x/y layer, a symbol of 7 bits, its model chosen by the last point's returns (first,
//      last) and whether its GPS time changed: the scanner channel changed (64), the point source
//      (32), the GPS time (16), the scan angle (8), the number of returns (4), and how the return
//      number changed (3: same, +1, -1, or coded).
//   2. A changed scanner channel is coded as the step to it (1 to 3, mod 4). Each channel is a
//      context of its own (models and last point); a channel first seen in the chunk starts from
//      the last point of the channel before it.
//   3. The number of returns n (a symbol, model by the last n) and the return number r (+1, -1,
//      a symbol by the last r when the time changed, else a step of 2 to 14) give a context m (0
//      to 5), a level l (0 to 7) and the point's return kind (first, last, single).
//   4. x and y: a difference predicted by the streaming median of the last five of the same m and
//      time change, y's context also from x's k; z in its layer, predicted by the last z of level l.
//   5. Each other layer, when not empty: classification (a symbol, model by the last class and
//      single return), flags (edge, scan direction, classification flags: a symbol by the last
//      ones), intensity (by the last of the same return kind and time change), scan angle and
//      point source (when changed, predicted by the last), user data (a symbol by the last / 4),
//      GPS time (when changed: GPSTIME11 v2's multiplier scheme, up to four sequences per channel).
// RGB14 (6), one layer; RGBNIR14 (8), two (RGB, NIR): RGB12 v2's coding of colour bytes, per
//   channel; NIR's two bytes each corrected by a symbol. BYTE14: one layer per extra byte, each
//   the last plus a symbol (mod 256), per channel.
// Version 3 of the items after POINT14 keeps predicting from the previous channel's last values
// when the point switches to a channel already seen in the chunk (and writes them there); version 4
// uses that channel's own. POINT14 v3 and v4 decode their own fields alike, but POINT14 v3 tells
// the items after it the channel only on a point that switches channel, and channel 0 on every
// other point (the reference starts each point's context at 0 and only v3's switch sets it), so
// that the colours and extra bytes of a v3 file whose points leave channel 0 flip between their
// channel's context and channel 0's: LASzip and laz-perf decode PDAL's tindex clips so.

#include <algorithm>
#include <array>
#include <cstring>
#include <vector>

#include "engine/io/byte_order.h"
#include "engine/io/laz_integer_decompressor.h"
#include "engine/io/laz_layered_items.h"
#include "engine/io/laz_streaming_median.h"

namespace plumb::io {
namespace {

constexpr unsigned kChannels = 4;

// Context m of [number of returns n][return number r]: the regular pairs of up to 3 returns take
// 0 to 5; the rest, and files numbering returns from 0 or mixing r and n up, fold onto 3 to 5.
constexpr std::array<std::array<std::uint8_t, 16>, 16> kReturnContext{{
    {0, 1, 2, 3, 4, 5, 3, 4, 4, 5, 5, 5, 5, 5, 5, 5},
    {1, 0, 1, 3, 3, 3, 3, 3, 3, 3, 3, 3, 3, 3, 3, 3},
    {2, 1, 2, 4, 4, 4, 4, 4, 4, 4, 4, 3, 3, 3, 3, 3},
    {3, 3, 4, 5, 4, 4, 4, 4, 4, 4, 4, 4, 4, 4, 4, 4},
    {4, 3, 4, 4, 5, 4, 4, 4, 4, 4, 4, 4, 4, 4, 4, 4},
    {5, 3, 4, 4, 4, 5, 4, 4, 4, 4, 4, 4, 4, 4, 4, 4},
    {3, 3, 4, 4, 4, 4, 5, 4, 4, 4, 4, 4, 4, 4, 4, 4},
    {4, 3, 4, 4, 4, 4, 4, 5, 4, 4, 4, 4, 4, 4, 4, 4},
    {4, 3, 4, 4, 4, 4, 4, 4, 5, 4, 4, 4, 4, 4, 4, 4},
    {5, 3, 4, 4, 4, 4, 4, 4, 4, 5, 4, 4, 4, 4, 4, 4},
    {5, 3, 4, 4, 4, 4, 4, 4, 4, 4, 5, 4, 4, 4, 4, 4},
    {5, 3, 3, 4, 4, 4, 4, 4, 4, 4, 4, 5, 5, 4, 4, 4},
    {5, 3, 3, 4, 4, 4, 4, 4, 4, 4, 4, 5, 5, 5, 4, 4},
    {5, 3, 3, 4, 4, 4, 4, 4, 4, 4, 4, 4, 5, 5, 5, 4},
    {5, 3, 3, 4, 4, 4, 4, 4, 4, 4, 4, 4, 4, 5, 5, 5},
    {5, 3, 3, 4, 4, 4, 4, 4, 4, 4, 4, 4, 4, 4, 5, 5},
}};

// Level l: |n - r|, how far the return is from the last one, at most 7.
constexpr unsigned returnLevel(unsigned n, unsigned r) {
  return std::min(n > r ? n - r : r - n, 7u);
}

std::int32_t wrappingAdd(std::int32_t a, std::int32_t b) {
  return static_cast<std::int32_t>(static_cast<std::uint32_t>(a) + static_cast<std::uint32_t>(b));
}

std::int32_t wrappingMultiply(std::int32_t a, std::int32_t b) {
  return static_cast<std::int32_t>(static_cast<std::uint32_t>(a) * static_cast<std::uint32_t>(b));
}

// A LAS 1.4 point's fields as POINT14 predicts them.
struct Point14 {
  std::int32_t x = 0, y = 0, z = 0;
  std::uint16_t intensity = 0;
  unsigned return_number = 0, number_of_returns = 0;  // 4 bits each
  unsigned classification_flags = 0, scanner_channel = 0, scan_direction = 0, edge = 0;
  unsigned classification = 0, user_data = 0;
  std::int16_t scan_angle = 0;
  std::uint16_t source_id = 0;
  std::uint64_t gps_time = 0;  // the double's bits
  bool gps_time_changed = false;

  static Point14 parse(const std::byte* in) {
    Point14 p;
    p.x = loadLittleEndian<std::int32_t>(in);
    p.y = loadLittleEndian<std::int32_t>(in + 4);
    p.z = loadLittleEndian<std::int32_t>(in + 8);
    p.intensity = loadLittleEndian<std::uint16_t>(in + 12);
    const auto returns = std::to_integer<unsigned>(in[14]);
    p.return_number = returns & 15u;
    p.number_of_returns = returns >> 4;
    const auto flags = std::to_integer<unsigned>(in[15]);
    p.classification_flags = flags & 15u;
    p.scanner_channel = (flags >> 4) & 3u;
    p.scan_direction = (flags >> 6) & 1u;
    p.edge = flags >> 7;
    p.classification = std::to_integer<unsigned>(in[16]);
    p.user_data = std::to_integer<unsigned>(in[17]);
    p.scan_angle = loadLittleEndian<std::int16_t>(in + 18);
    p.source_id = loadLittleEndian<std::uint16_t>(in + 20);
    p.gps_time = loadLittleEndian<std::uint64_t>(in + 22);
    return p;
  }

  void write(std::byte* out) const {
    packLittleEndian(out, x);
    packLittleEndian(out + 4, y);
    packLittleEndian(out + 8, z);
    packLittleEndian(out + 12, intensity);
    out[14] = static_cast<std::byte>(return_number | (number_of_returns << 4));
    out[15] =
        static_cast<std::byte>(classification_flags | (scanner_channel << 4) | (scan_direction << 6) | (edge << 7));
    out[16] = static_cast<std::byte>(classification);
    out[17] = static_cast<std::byte>(user_data);
    packLittleEndian(out + 18, scan_angle);
    packLittleEndian(out + 20, source_id);
    packLittleEndian(out + 22, gps_time);
  }
};

constexpr std::size_t kPoint14Bytes = 30;

class Point14V3 final : public LazLayeredItemDecoder {
 public:
  explicit Point14V3(bool version4) : version4_(version4) {}

  std::size_t layerCount() const override { return kLayers; }
  std::string layerName(std::size_t layer) const override {
    static constexpr std::array<const char*, kLayers> kNames{
        "POINT14 x/y and returns", "POINT14 z",          "POINT14 classification", "POINT14 flags",
        "POINT14 intensity",       "POINT14 scan angle", "POINT14 user data",      "POINT14 point source",
        "POINT14 GPS time"};
    return kNames[layer];
  }

  void start(const std::byte* first, std::span<LazLayer* const> layers, unsigned& context) override {
    std::copy(layers.begin(), layers.end(), layers_.begin());
    used_ = {};
    const Point14 point = Point14::parse(first);
    current_ = point.scanner_channel;
    context = current_;
    startChannel(current_, point);
  }

  void decode(std::byte* out, unsigned& context) override {
    Channel* channel = used_[current_];
    LazArithmeticDecoder& xy = layers_[kXy]->decoder;
    {
      const Point14& last = channel->last;
      const unsigned last_kind = (last.return_number == 1 ? 1u : 0u) +
                                 (last.return_number >= last.number_of_returns ? 2u : 0u) +
                                 (last.gps_time_changed ? 4u : 0u);
      const std::uint32_t changed = xy.decodeSymbol(channel->changed[last_kind]);
      if (changed & 64u) {
        const std::uint32_t step = xy.decodeSymbol(channel->scanner_channel);
        const unsigned next = (current_ + step + 1) % kChannels;
        if (!used_[next]) startChannel(next, channel->last);
        current_ = next;
        context = next;
        channel = used_[next];
        channel->last.scanner_channel = next;
      }
      // Version 3 names the channel to the items after it only on the point that switches; on
      // the others they are told channel 0 (the reference's context starts at 0 for each point).
      // Version 4 always names the current one.
      if (version4_) context = current_;
      changed_ = changed;
    }
    Point14& last = channel->last;
    const bool source_changed = (changed_ & 32u) != 0;
    const unsigned time_changed = (changed_ & 16u) != 0 ? 1u : 0u;
    const bool scan_angle_changed = (changed_ & 8u) != 0;

    if (changed_ & 4u) {
      last.number_of_returns = xy.decodeSymbol(channel->number_of_returns[last.number_of_returns]);
    }
    const unsigned n = last.number_of_returns;
    switch (changed_ & 3u) {
      case 0:
        break;
      case 1:
        last.return_number = (last.return_number + 1) % 16;
        break;
      case 2:
        last.return_number = (last.return_number + 15) % 16;
        break;
      default:
        if (time_changed) {
          last.return_number = xy.decodeSymbol(channel->return_number[last.return_number]);
        } else {
          const std::uint32_t step = xy.decodeSymbol(channel->return_number_same_time);
          last.return_number = (last.return_number + step + 2) % 16;
        }
        break;
    }
    const unsigned r = last.return_number;
    const unsigned m = kReturnContext[n][r];
    const unsigned l = returnLevel(n, r);
    const unsigned kind = (r == 1 ? 1u : 0u) + (r >= n ? 2u : 0u);
    const unsigned single = n == 1 ? 1u : 0u;

    const std::size_t median_at = (m << 1) | time_changed;
    const std::int32_t x_diff = channel->dx.decompress(xy, channel->x_medians[median_at].median(), single);
    last.x = wrappingAdd(last.x, x_diff);
    channel->x_medians[median_at].add(x_diff);
    unsigned k = channel->dx.k();
    const std::int32_t y_diff =
        channel->dy.decompress(xy, channel->y_medians[median_at].median(), single + (k < 20 ? k & ~1u : 20u));
    last.y = wrappingAdd(last.y, y_diff);
    channel->y_medians[median_at].add(y_diff);

    if (active(kZ)) {
      k = (channel->dx.k() + channel->dy.k()) / 2;
      last.z = channel->z.decompress(layers_[kZ]->decoder, channel->last_z[l], single + (k < 18 ? k & ~1u : 18u));
      channel->last_z[l] = last.z;
    }
    if (active(kClassification)) {
      const std::size_t model = ((last.classification & 0x1Fu) << 1) + (kind == 3 ? 1u : 0u);
      last.classification = layers_[kClassification]->decoder.decodeSymbol(channel->classification[model]);
    }
    if (active(kFlags)) {
      const std::size_t model = (last.edge << 5) | (last.scan_direction << 4) | last.classification_flags;
      const std::uint32_t flags = layers_[kFlags]->decoder.decodeSymbol(channel->flags[model]);
      last.edge = (flags >> 5) & 1u;
      last.scan_direction = (flags >> 4) & 1u;
      last.classification_flags = flags & 15u;
    }
    if (active(kIntensity)) {
      const std::size_t at = (kind << 1) | time_changed;
      last.intensity = static_cast<std::uint16_t>(
          channel->intensity.decompress(layers_[kIntensity]->decoder, channel->last_intensity[at], kind));
      channel->last_intensity[at] = last.intensity;
    }
    if (active(kScanAngle) && scan_angle_changed) {
      last.scan_angle = static_cast<std::int16_t>(static_cast<std::uint16_t>(
          channel->scan_angle.decompress(layers_[kScanAngle]->decoder, last.scan_angle, time_changed)));
    }
    if (active(kUserData)) {
      last.user_data = layers_[kUserData]->decoder.decodeSymbol(channel->user_data[last.user_data / 4]);
    }
    if (active(kSource) && source_changed) {
      last.source_id =
          static_cast<std::uint16_t>(channel->source_id.decompress(layers_[kSource]->decoder, last.source_id, 0));
    }
    if (active(kGpsTime) && time_changed) {
      decodeTime(*channel, layers_[kGpsTime]->decoder);
      last.gps_time = channel->time[channel->sequence];
    }
    last.write(out);
    last.gps_time_changed = time_changed != 0;
  }

 private:
  enum Layer : std::size_t {
    kXy,
    kZ,
    kClassification,
    kFlags,
    kIntensity,
    kScanAngle,
    kUserData,
    kSource,
    kGpsTime,
    kLayers
  };

  static constexpr std::int32_t kMaxMultiplier = 500;
  static constexpr std::int32_t kMinMultiplier = -10;
  static constexpr std::uint32_t kJump = kMaxMultiplier - kMinMultiplier + 1;       // 511; above: switches
  static constexpr std::uint32_t kTimeCodes = kMaxMultiplier - kMinMultiplier + 5;  // 515

  // The models and last values of one scanner channel.
  struct Channel {
    Point14 last;
    std::array<std::uint16_t, 8> last_intensity{};
    std::array<StreamingMedian5, 12> x_medians, y_medians;
    std::array<std::int32_t, 8> last_z{};

    std::vector<LazSymbolModel> changed = std::vector<LazSymbolModel>(8, LazSymbolModel(128));
    LazSymbolModel scanner_channel{3};
    LazModelSet number_of_returns{16, 16}, return_number{16, 16};
    LazSymbolModel return_number_same_time{13};
    LazIntegerDecompressor dx{32, 2}, dy{32, 22}, z{32, 20};
    LazModelSet classification{64, 256}, flags{64, 64}, user_data{64, 256};
    LazIntegerDecompressor intensity{16, 4}, scan_angle{16, 2}, source_id{16, 1};

    unsigned sequence = 0, newest = 0;
    std::array<std::uint64_t, 4> time{};
    std::array<std::int32_t, 4> time_diff{};
    std::array<int, 4> extreme_count{};
    LazSymbolModel time_multiplier{kTimeCodes}, time_after_zero{5};
    LazIntegerDecompressor time_diffs{32, 9};
  };

  bool active(Layer layer) const { return layers_[layer]->bytes != 0; }

  // Starts channel `c` for the chunk from `from` (the chunk's first point, or the last point of
  // the channel the stream switches from).
  void startChannel(unsigned c, const Point14& from) {
    if (!channels_[c]) channels_[c] = std::make_unique<Channel>();
    Channel& channel = *channels_[c];
    for (LazSymbolModel& model : channel.changed) model.reset();
    channel.scanner_channel.reset();
    channel.number_of_returns.reset();
    channel.return_number.reset();
    channel.return_number_same_time.reset();
    channel.dx.reset();
    channel.dy.reset();
    channel.z.reset();
    channel.classification.reset();
    channel.flags.reset();
    channel.user_data.reset();
    channel.intensity.reset();
    channel.scan_angle.reset();
    channel.source_id.reset();
    channel.time_multiplier.reset();
    channel.time_after_zero.reset();
    channel.time_diffs.reset();
    for (StreamingMedian5& median : channel.x_medians) median.reset();
    for (StreamingMedian5& median : channel.y_medians) median.reset();
    channel.last_z.fill(from.z);
    channel.last_intensity.fill(from.intensity);
    channel.sequence = channel.newest = 0;
    channel.time = {from.gps_time, 0, 0, 0};
    channel.time_diff = {};
    channel.extreme_count = {};
    channel.last = from;
    channel.last.gps_time_changed = false;
    used_[c] = &channel;
  }

  // GPSTIME11 v2's scheme on the channel's sequences; the loop stands for the reference's
  // recursion on a switch of sequence (a corrupt stream cannot exhaust the stack).
  static void decodeTime(Channel& ch, LazArithmeticDecoder& decoder) {
    for (;;) {
      unsigned& s = ch.sequence;
      if (ch.time_diff[s] == 0) {
        const std::uint32_t code = decoder.decodeSymbol(ch.time_after_zero);
        if (code == 0) {  // a difference of 32 bits
          ch.time_diff[s] = ch.time_diffs.decompress(decoder, 0, 0);
          addToTime(ch, ch.time_diff[s]);
          ch.extreme_count[s] = 0;
        } else if (code == 1) {
          jump(ch, decoder);
        } else {
          s = (s + code - 1) & 3u;
          continue;
        }
        return;
      }
      const std::uint32_t code = decoder.decodeSymbol(ch.time_multiplier);
      if (code == 1) {
        addToTime(ch, ch.time_diffs.decompress(decoder, ch.time_diff[s], 1));
        ch.extreme_count[s] = 0;
      } else if (code < kJump) {
        std::int32_t diff = 0;
        if (code == 0) {
          diff = ch.time_diffs.decompress(decoder, 0, 7);
          adoptAfterRepeats(ch, diff);
        } else if (code < static_cast<std::uint32_t>(kMaxMultiplier)) {
          diff = ch.time_diffs.decompress(decoder, wrappingMultiply(static_cast<std::int32_t>(code), ch.time_diff[s]),
                                          code < 10 ? 2 : 3);
        } else if (code == static_cast<std::uint32_t>(kMaxMultiplier)) {
          diff = ch.time_diffs.decompress(decoder, wrappingMultiply(kMaxMultiplier, ch.time_diff[s]), 4);
          adoptAfterRepeats(ch, diff);
        } else {
          // Codes above 500 stand for the multipliers -1 to -10.
          const std::int32_t multiplier = kMaxMultiplier - static_cast<std::int32_t>(code);
          if (multiplier > kMinMultiplier) {
            diff = ch.time_diffs.decompress(decoder, wrappingMultiply(multiplier, ch.time_diff[s]), 5);
          } else {
            diff = ch.time_diffs.decompress(decoder, wrappingMultiply(kMinMultiplier, ch.time_diff[s]), 6);
            adoptAfterRepeats(ch, diff);
          }
        }
        addToTime(ch, diff);
      } else if (code == kJump) {
        jump(ch, decoder);
      } else {
        s = (s + code - kJump) & 3u;
        continue;
      }
      return;
    }
  }

  static void addToTime(Channel& ch, std::int32_t diff) {
    ch.time[ch.sequence] += static_cast<std::uint64_t>(static_cast<std::int64_t>(diff));
  }

  // A new sequence: the high 32 bits predicted by the current time's, the low 32 bits raw.
  static void jump(Channel& ch, LazArithmeticDecoder& decoder) {
    ch.newest = (ch.newest + 1) & 3u;
    const auto high_prediction = static_cast<std::int32_t>(static_cast<std::uint32_t>(ch.time[ch.sequence] >> 32));
    const auto high = static_cast<std::uint32_t>(ch.time_diffs.decompress(decoder, high_prediction, 8));
    ch.time[ch.newest] = (std::uint64_t{high} << 32) | decoder.readInt();
    ch.sequence = ch.newest;
    ch.time_diff[ch.sequence] = 0;
    ch.extreme_count[ch.sequence] = 0;
  }

  // An unusual difference becomes the new prediction only once it has come four times running.
  static void adoptAfterRepeats(Channel& ch, std::int32_t diff) {
    if (++ch.extreme_count[ch.sequence] > 3) {
      ch.time_diff[ch.sequence] = diff;
      ch.extreme_count[ch.sequence] = 0;
    }
  }

  bool version4_;
  std::array<LazLayer*, kLayers> layers_{};
  std::array<std::unique_ptr<Channel>, kChannels> channels_;  // kept across chunks, reset when used
  std::array<Channel*, kChannels> used_{};                    // those started in this chunk
  unsigned current_ = 0;
  std::uint32_t changed_ = 0;
};

// The items after POINT14 keep their last values per channel; `Values` holds one channel's.
// Version 3 keeps predicting from (and writing to) the values of the channel it switched from
// when it switches to a channel already started in the chunk; version 4 uses the channel's own.
template <typename Values>
class PerChannel {
 public:
  explicit PerChannel(bool version4) : version4_(version4) {}

  // The chunk's first point starts channel `context`.
  template <typename Start>
  Values& startChunk(unsigned context, Start&& start) {
    used_ = {};
    current_ = context;
    return startChannel(context, start);
  }

  // Follows POINT14's context; returns the channel whose models decode the point, and in `last`
  // the channel whose last values predict it (for this point only).
  template <typename Start>
  Values& follow(unsigned context, Start&& start, Values*& last) {
    unsigned last_at = current_;
    if (context != current_) {
      current_ = context;
      if (!used_[context]) {
        startChannel(context, start, channels_[last_at].get());
        last_at = context;
      } else if (version4_) {
        last_at = context;
      }
    }
    last = channels_[last_at].get();
    return *channels_[current_];
  }

 private:
  template <typename Start>
  Values& startChannel(unsigned c, Start& start, const Values* from = nullptr) {
    if (!channels_[c]) channels_[c] = std::make_unique<Values>();
    start(*channels_[c], from);
    used_[c] = true;
    return *channels_[c];
  }

  bool version4_;
  std::array<std::unique_ptr<Values>, kChannels> channels_;
  std::array<bool, kChannels> used_{};
  unsigned current_ = 0;
};

// The colour bytes of RGB12 v2, RGB14 and RGBNIR14 (which name the same coding).
struct RgbModels {
  LazSymbolModel used{128};
  std::vector<LazSymbolModel> corrections = std::vector<LazSymbolModel>(6, LazSymbolModel(256));
  void reset() {
    used.reset();
    for (LazSymbolModel& model : corrections) model.reset();
  }
};

unsigned lowByte(unsigned v) {
  return v & 0xFFu;
}
unsigned highByte(unsigned v) {
  return v >> 8;
}
unsigned clampToByte(int v) {
  return static_cast<unsigned>(std::clamp(v, 0, 255));
}

// Decodes a colour predicted by `last` into `colour`.
void decodeRgb(LazArithmeticDecoder& decoder, RgbModels& models, const std::array<std::uint16_t, 4>& last,
               std::array<std::uint16_t, 4>& colour) {
  const std::uint32_t used = decoder.decodeSymbol(models.used);
  auto corrected = [&](unsigned bit, unsigned prediction) {
    return (decoder.decodeSymbol(models.corrections[bit]) + prediction) & 0xFFu;
  };
  const unsigned red_low = (used & 1u) ? corrected(0, lowByte(last[0])) : lowByte(last[0]);
  const unsigned red_high = (used & 2u) ? corrected(1, highByte(last[0])) : highByte(last[0]);
  colour[0] = static_cast<std::uint16_t>(red_low | (red_high << 8));
  if ((used & 64u) == 0) {  // grey
    colour[1] = colour[2] = colour[0];
    return;
  }
  int step = static_cast<int>(red_low) - static_cast<int>(lowByte(last[0]));
  unsigned green_low = lowByte(last[1]), blue_low = lowByte(last[2]);
  if (used & 4u) green_low = corrected(2, clampToByte(step + static_cast<int>(lowByte(last[1]))));
  if (used & 16u) {
    step = (step + static_cast<int>(green_low) - static_cast<int>(lowByte(last[1]))) / 2;
    blue_low = corrected(4, clampToByte(step + static_cast<int>(lowByte(last[2]))));
  }
  step = static_cast<int>(red_high) - static_cast<int>(highByte(last[0]));
  unsigned green_high = highByte(last[1]), blue_high = highByte(last[2]);
  if (used & 8u) green_high = corrected(3, clampToByte(step + static_cast<int>(highByte(last[1]))));
  if (used & 32u) {
    step = (step + static_cast<int>(green_high) - static_cast<int>(highByte(last[1]))) / 2;
    blue_high = corrected(5, clampToByte(step + static_cast<int>(highByte(last[2]))));
  }
  colour[1] = static_cast<std::uint16_t>(green_low | (green_high << 8));
  colour[2] = static_cast<std::uint16_t>(blue_low | (blue_high << 8));
}

// RGB14 (6 bytes, one layer) and RGBNIR14 (8 bytes, layers RGB and NIR).
class RgbNir14 final : public LazLayeredItemDecoder {
 public:
  RgbNir14(bool nir, bool version4) : nir_(nir), channels_(version4) {}

  std::size_t layerCount() const override { return nir_ ? 2 : 1; }
  std::string layerName(std::size_t layer) const override {
    if (!nir_) return "RGB14";
    return layer == 0 ? "RGBNIR14 RGB" : "RGBNIR14 NIR";
  }

  void start(const std::byte* first, std::span<LazLayer* const> layers, unsigned& context) override {
    rgb_ = layers[0];
    nir_layer_ = nir_ ? layers[1] : nullptr;
    std::array<std::uint16_t, 4> values{};
    for (std::size_t c = 0; c < (nir_ ? 4u : 3u); ++c) values[c] = loadLittleEndian<std::uint16_t>(first + 2 * c);
    channels_.startChunk(context, [&](Values& v, const Values*) {
      v.rgb.reset();
      v.nir_used.reset();
      for (LazSymbolModel& model : v.nir_corrections) model.reset();
      v.last = values;
    });
  }

  void decode(std::byte* out, unsigned& context) override {
    Values* last = nullptr;
    Values& models = channels_.follow(
        context,
        [](Values& v, const Values* from) {
          v.rgb.reset();
          v.nir_used.reset();
          for (LazSymbolModel& model : v.nir_corrections) model.reset();
          v.last = from->last;
        },
        last);
    std::array<std::uint16_t, 4> colour = last->last;
    if (rgb_->bytes != 0) {
      decodeRgb(rgb_->decoder, models.rgb, last->last, colour);
      std::copy_n(colour.begin(), 3, last->last.begin());
    }
    if (nir_ && nir_layer_->bytes != 0) {
      LazArithmeticDecoder& decoder = nir_layer_->decoder;
      const std::uint32_t used = decoder.decodeSymbol(models.nir_used);
      unsigned low = lowByte(last->last[3]), high = highByte(last->last[3]);
      if (used & 1u) low = (decoder.decodeSymbol(models.nir_corrections[0]) + low) & 0xFFu;
      if (used & 2u) high = (decoder.decodeSymbol(models.nir_corrections[1]) + high) & 0xFFu;
      colour[3] = static_cast<std::uint16_t>(low | (high << 8));
      last->last[3] = colour[3];
    }
    for (std::size_t c = 0; c < (nir_ ? 4u : 3u); ++c) packLittleEndian(out + 2 * c, colour[c]);
  }

 private:
  struct Values {
    RgbModels rgb;
    LazSymbolModel nir_used{4};
    std::vector<LazSymbolModel> nir_corrections = std::vector<LazSymbolModel>(2, LazSymbolModel(256));
    std::array<std::uint16_t, 4> last{};
  };

  bool nir_;
  PerChannel<Values> channels_;
  LazLayer* rgb_ = nullptr;
  LazLayer* nir_layer_ = nullptr;
};

// BYTE14: one layer per extra byte.
class Byte14 final : public LazLayeredItemDecoder {
 public:
  Byte14(std::size_t count, bool version4) : count_(count), channels_(version4), layers_(count) {}

  std::size_t layerCount() const override { return count_; }
  std::string layerName(std::size_t layer) const override { return "BYTE14 extra byte " + std::to_string(layer + 1); }

  void start(const std::byte* first, std::span<LazLayer* const> layers, unsigned& context) override {
    std::copy(layers.begin(), layers.end(), layers_.begin());
    channels_.startChunk(context, [&](Values& v, const Values*) {
      resetModels(v);
      v.last.assign(first, first + count_);
    });
  }

  void decode(std::byte* out, unsigned& context) override {
    Values* last = nullptr;
    Values& models = channels_.follow(
        context,
        [&](Values& v, const Values* from) {
          resetModels(v);
          v.last = from->last;
        },
        last);
    for (std::size_t i = 0; i < count_; ++i) {
      if (layers_[i]->bytes != 0) {
        const std::uint32_t step = layers_[i]->decoder.decodeSymbol(models.models[i]);
        last->last[i] = static_cast<std::byte>((std::to_integer<std::uint32_t>(last->last[i]) + step) & 0xFFu);
      }
      out[i] = last->last[i];
    }
  }

 private:
  struct Values {
    std::vector<LazSymbolModel> models;
    std::vector<std::byte> last;
  };

  void resetModels(Values& v) const {
    if (v.models.empty()) v.models.assign(count_, LazSymbolModel(256));
    for (LazSymbolModel& model : v.models) model.reset();
  }

  std::size_t count_;
  PerChannel<Values> channels_;
  std::vector<LazLayer*> layers_;
};

}  // namespace

std::unique_ptr<LazLayeredItemDecoder> makeLazLayeredItemDecoder(const LazItem& item) {
  if (item.version != 3 && item.version != 4) return nullptr;
  const bool version4 = item.version == 4;
  switch (static_cast<LazItemType>(item.type)) {
    case LazItemType::kPoint14:
      if (item.size == kPoint14Bytes) return std::make_unique<Point14V3>(version4);
      break;
    case LazItemType::kRgb14:
      if (item.size == 6) return std::make_unique<RgbNir14>(false, version4);
      break;
    case LazItemType::kRgbNir14:
      if (item.size == 8) return std::make_unique<RgbNir14>(true, version4);
      break;
    case LazItemType::kByte14:
      if (item.size >= 1) return std::make_unique<Byte14>(item.size, version4);
      break;
    default:
      break;
  }
  return nullptr;
}

}  // namespace plumb::io
