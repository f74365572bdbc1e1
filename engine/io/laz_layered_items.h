#pragma once
// The items of the layered LASzip coder (compressor 3, LAS 1.4 point formats 6 to 8), after the
// LASzip reference implementation, src/lasreaditemcompressed_v3.cpp and
// src/lasreaditemcompressed_v4.cpp (read, not copied); Isenburg 2013, "LASzip: lossless
// compression of LiDAR data", PE&RS 79(2).
//
// A layered chunk stores each field group of its points in a layer of its own, arithmetic-coded
// by its own decoder over that layer's bytes (laz_point_decompressor.h reads the layer sizes and
// hands each item its layers). An empty layer means the field does not change within the chunk:
// every point repeats the chunk's first value.
//
// POINT14 tracks up to four scanner channels ("contexts"), each with its own models and its own
// last point; it sets the context for the items after it (RGB14, RGBNIR14, BYTE14), which keep
// models and last values per context too.

#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <string>

#include "engine/io/file_source.h"
#include "engine/io/laz_arithmetic_decoder.h"
#include "engine/io/laz_items.h"

namespace plumb::io {

// One layer of a chunk: its bytes and the decoder over them. `bytes` 0: the layer is empty (the
// decoder is never started).
struct LazLayer {
  explicit LazLayer(FileSource& source) : input(source), decoder(input) {}
  LazLayer(const LazLayer&) = delete;
  LazLayer& operator=(const LazLayer&) = delete;

  LazByteInput input;
  LazArithmeticDecoder decoder;
  std::uint32_t bytes = 0;
};

class LazLayeredItemDecoder {
 public:
  virtual ~LazLayeredItemDecoder() = default;

  // How many layers the item codes, and the name of each (in errors).
  virtual std::size_t layerCount() const = 0;
  virtual std::string layerName(std::size_t layer) const = 0;

  // Starts a chunk: `first` holds the item's bytes of the chunk's first point (stored raw);
  // `layers` (layerCount() of them) are set up and started for the chunk and outlive it.
  // POINT14 sets `context` (the first point's scanner channel); the others read it.
  virtual void start(const std::byte* first, std::span<LazLayer* const> layers, unsigned& context) = 0;

  // Decodes the next point's item bytes into `out` (the item's size). POINT14 may change
  // `context`; the items after it follow.
  virtual void decode(std::byte* out, unsigned& context) = 0;
};

// The decoder of a layered item: POINT14 (size 30), RGB14 (6), RGBNIR14 (8) or BYTE14 (>= 1),
// version 3 or 4; null for anything else (WAVEPACKET14 included). Defined in laz_items_v3.cpp.
std::unique_ptr<LazLayeredItemDecoder> makeLazLayeredItemDecoder(const LazItem& item);

}  // namespace plumb::io
