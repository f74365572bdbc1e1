#pragma once
// The items of a LAZ point and their decoders for the point-wise LASzip coder (compressors 1 and
// 2), after the LASzip reference implementation: src/laszip.hpp for the item types,
// src/lasreaditemcompressed_v1.cpp and src/lasreaditemcompressed_v2.cpp for the coders (read, not
// copied); Isenburg 2013, "LASzip: lossless compression of LiDAR data", PE&RS 79(2).
//
// A LAS record of point formats 0 to 3 is the concatenation of its items' bytes: POINT10 (20
// bytes: x y z, intensity, the return byte, classification, scan angle rank, user data, point
// source id), GPSTIME11 (8: the GPS time), RGB12 (6: red green blue) and BYTE (the record's
// extra bytes). Each decoder turns the compressed stream into exactly those bytes, so that LAS
// and LAZ share one record decoder.
//
// Every chunk starts with its first point stored raw; start() hands each decoder its item's raw
// bytes and resets its models. decode() then writes the next point's item bytes.

#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>

#include "engine/io/laz_arithmetic_decoder.h"

namespace plumb::io {

// The item types of the laszip VLR (src/laszip.hpp). Types 1 to 5 (SHORT to DOUBLE) were never
// written; 10 to 14 belong to the layered coder of LAS 1.4 point formats 6 to 10.
enum class LazItemType : std::uint16_t {
  kByte = 0,
  kPoint10 = 6,
  kGpsTime11 = 7,
  kRgb12 = 8,
  kWavePacket13 = 9,
  kPoint14 = 10,
  kRgb14 = 11,
  kRgbNir14 = 12,
  kWavePacket14 = 13,
  kByte14 = 14,
};

// One entry of the laszip VLR's item list; `type` as stored (possibly none of LazItemType's).
struct LazItem {
  std::uint16_t type = 0;
  std::uint16_t size = 0;     // bytes per point
  std::uint16_t version = 0;  // of the item's coder: 1 or 2 for the point-wise coder
};

class LazItemDecoder {
 public:
  virtual ~LazItemDecoder() = default;

  // Starts a chunk: `first` holds the item's bytes of the chunk's first point (stored raw).
  virtual void start(const std::byte* first) = 0;

  // Decodes the next point's item bytes into `out` (the item's size).
  virtual void decode(LazArithmeticDecoder& decoder, std::byte* out) = 0;
};

// 256 symbol models of 256 symbols, one per value of the previous point's byte (POINT10's return
// byte, classification and user data), made when first used: most files use a few. reset()
// resets those made, which then decode as new ones would.
class LazModelsByPreviousByte {
 public:
  LazSymbolModel& operator[](std::uint8_t previous) {
    std::unique_ptr<LazSymbolModel>& model = models_[previous];
    if (!model) model = std::make_unique<LazSymbolModel>(256);
    return *model;
  }
  void reset() {
    for (const std::unique_ptr<LazSymbolModel>& model : models_) {
      if (model) model->reset();
    }
  }

 private:
  std::array<std::unique_ptr<LazSymbolModel>, 256> models_;
};

// The decoders of version 1 and of version 2 of an item of type POINT10 (size 20), GPSTIME11 (8),
// RGB12 (6) or BYTE (any size >= 1); null for any other type or size. Defined in
// laz_items_v1.cpp and laz_items_v2.cpp.
std::unique_ptr<LazItemDecoder> makeLazItemDecoderV1(const LazItem& item);
std::unique_ptr<LazItemDecoder> makeLazItemDecoderV2(const LazItem& item);

// The decoder of `item` (version 1 or 2), or null when the point-wise coder has none.
inline std::unique_ptr<LazItemDecoder> makeLazItemDecoder(const LazItem& item) {
  if (item.version == 1) return makeLazItemDecoderV1(item);
  if (item.version == 2) return makeLazItemDecoderV2(item);
  return nullptr;
}

}  // namespace plumb::io
