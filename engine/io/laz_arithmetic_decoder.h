#pragma once
// The entropy decoder of LAZ: the range decoder of the LASzip point-wise coder, after the LASzip
// reference implementation (src/arithmeticdecoder.cpp, src/arithmeticmodel.cpp; read, not
// copied), which adapts Amir Said's FastAC (A. Said, "Introduction to Arithmetic Coding: Theory
// and Practice", HP Labs report HPL-2004-76, 2004: 32-bit integer interval arithmetic with
// periodic model updates). Isenburg 2013, "LASzip: lossless compression of LiDAR data", PE&RS
// 79(2), describes the coder in words; the reference implementation is the specification.
//
// 32-bit interval: `length` is renormalised by whole bytes whenever it falls below 2^24, `value`
// is the code point inside the interval. Three kinds of decoding:
//   - adaptive bits (LazBitModel): probability of 0 in 13 bits, recomputed after 4, 5, 6, ... up
//     to 64 bits (the update cycle grows by 5/4), counts halved beyond 2^13;
//   - adaptive symbols of 2 to 2048 values (LazSymbolModel): a cumulative distribution in 15 bits,
//     recomputed on the same growing cycle (at most 8 (n + 6) symbols), counts halved beyond 2^15;
//     above 16 symbols a look-up table narrows the search before a bisection;
//   - raw bits, 1 to 32, of uniform probability.
// Every operation is bit-exact with the reference: a decoded stream only matches when each
// multiply, shift and truncation is the same.
//
// Corrupt input never reads outside the models' arrays: it decodes garbage until the chunk's
// bytes run out, and LazByteInput then throws plumb::Error with the file and the byte offset.

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "engine/io/file_source.h"

namespace plumb::io {

// The compressed bytes of one stretch of a file, [begin, end), read ahead in blocks through a
// FileSource: the arithmetic decoder's input. Running past `end` is an error (a truncated or
// corrupt chunk), never a read of what follows.
class LazByteInput {
 public:
  explicit LazByteInput(FileSource& source) : source_(source) {}

  // Reads from `begin` up to `end` (<= the file's size) next. `what` names the stretch in errors,
  // e.g. "chunk 2 of 3".
  void reset(std::uint64_t begin, std::uint64_t end, std::string what);

  // The next byte; throws plumb::Error at `end`.
  std::uint8_t next() {
    if (at_ == filled_) refill();
    return buffer_[at_++];
  }

  // Exactly `out.size()` bytes (a chunk's first point, stored raw).
  void read(std::span<std::byte> out);

  // File offset of the byte next() returns next.
  std::uint64_t offset() const { return buffer_start_ + at_; }
  std::uint64_t end() const { return end_; }
  const std::string& what() const { return what_; }
  const FileSource& source() const { return source_; }

 private:
  void refill();

  FileSource& source_;
  std::vector<std::uint8_t> buffer_;
  std::uint64_t buffer_start_ = 0;  // file offset of buffer_[0]
  std::size_t at_ = 0, filled_ = 0;
  std::uint64_t end_ = 0;
  std::string what_;
};

// An adaptive binary model. reset() returns it to equal probabilities.
class LazBitModel {
 public:
  LazBitModel() { reset(); }
  void reset();

 private:
  friend class LazArithmeticDecoder;
  void update();

  std::uint32_t update_cycle_ = 0, until_update_ = 0;
  std::uint32_t bit_0_probability_ = 0, bit_0_count_ = 0, bit_count_ = 0;
};

// An adaptive model of `symbols` values (2 to 2048). reset() returns it to equal frequencies.
class LazSymbolModel {
 public:
  explicit LazSymbolModel(std::uint32_t symbols);
  std::uint32_t symbols() const { return symbols_; }
  void reset();

 private:
  friend class LazArithmeticDecoder;
  void update();

  std::uint32_t symbols_;
  std::uint32_t last_symbol_;
  std::uint32_t table_size_ = 0, table_shift_ = 0;  // table_size_ 0: no look-up table
  std::uint32_t total_count_ = 0, update_cycle_ = 0, until_update_ = 0;
  std::vector<std::uint32_t> distribution_;  // cumulative, scaled to 2^15
  std::vector<std::uint32_t> counts_;
  std::vector<std::uint32_t> table_;  // table_size_ + 2 entries: first symbol per slice of the range
};

// The range decoder over a LazByteInput. start() before the first decode, at the beginning of
// each chunk's arithmetic-coded bytes.
class LazArithmeticDecoder {
 public:
  explicit LazArithmeticDecoder(LazByteInput& input) : input_(input) {}

  // Reads the first 4 bytes (the initial code point).
  void start();

  // Inline, below: the decoding of every field of every point goes through these.
  std::uint32_t decodeBit(LazBitModel& model);
  std::uint32_t decodeSymbol(LazSymbolModel& model);  // < model.symbols()

  // Raw bits of uniform probability; `bits` is 1 to 32. Corrupt input may give values of more
  // bits than asked for (the reference does the same); callers mask or fold what they use.
  std::uint32_t readBits(unsigned bits);
  std::uint16_t readShort();  // 16 raw bits
  std::uint32_t readInt();    // two readShort(), low half first
  std::uint64_t readInt64();  // two readInt(), low half first

  // The interval is renormalised when its length drops below 2^24 (one byte of precision left).
  static constexpr std::uint32_t kMinLength = 0x01000000u;
  static constexpr unsigned kBitLengthShift = 13;     // bit models' probabilities
  static constexpr unsigned kSymbolLengthShift = 15;  // symbol models' distributions

 private:
  std::uint32_t readUpTo19Bits(unsigned bits);
  void renormalise();

  LazByteInput& input_;
  std::uint32_t value_ = 0;
  std::uint32_t length_ = 0;
};

// ---- The hot paths, inline --------------------------------------------------------------------
// The state lives in locals while a symbol is decoded: the models' stores (uint32_t, like the
// state) would otherwise force the compiler to reload it after each.

inline void LazArithmeticDecoder::renormalise() {
  std::uint32_t value = value_, length = length_;
  do {
    value = (value << 8) | input_.next();
    length <<= 8;
  } while (length < kMinLength);
  value_ = value;
  length_ = length;
}

inline std::uint32_t LazArithmeticDecoder::decodeBit(LazBitModel& model) {
  const std::uint32_t bound = model.bit_0_probability_ * (length_ >> kBitLengthShift);
  std::uint32_t bit = 0;
  if (value_ < bound) {
    length_ = bound;
    ++model.bit_0_count_;
  } else {
    bit = 1;
    value_ -= bound;
    length_ -= bound;
  }
  if (length_ < kMinLength) renormalise();
  if (--model.until_update_ == 0) model.update();
  return bit;
}

inline std::uint32_t LazArithmeticDecoder::decodeSymbol(LazSymbolModel& model) {
  const std::uint32_t* const distribution = model.distribution_.data();
  const std::uint32_t value = value_;
  const std::uint32_t length = length_ >> kSymbolLengthShift;
  std::uint32_t symbol = 0;
  std::uint32_t low = 0;         // the symbol's interval start, scaled
  std::uint32_t high = length_;  // its end (the whole length for the last symbol)
  if (model.table_size_ != 0) {
    const std::uint32_t target = value / length;
    // Within the table for any valid stream (value < the old length); the clamp only keeps a
    // corrupt stream inside the array.
    const std::uint32_t slice = std::min(target >> model.table_shift_, model.table_size_);
    symbol = model.table_[slice];
    std::uint32_t above = model.table_[slice + 1] + 1;
    while (above > symbol + 1) {
      const std::uint32_t middle = (symbol + above) >> 1;
      if (distribution[middle] > target) {
        above = middle;
      } else {
        symbol = middle;
      }
    }
    low = distribution[symbol] * length;
    if (symbol != model.last_symbol_) high = distribution[symbol + 1] * length;
  } else {
    // Few symbols: bisect on the products directly.
    std::uint32_t above = model.symbols_;
    std::uint32_t middle = above >> 1;
    do {
      const std::uint32_t product = length * distribution[middle];
      if (product > value) {
        above = middle;
        high = product;
      } else {
        symbol = middle;
        low = product;
      }
      middle = (symbol + above) >> 1;
    } while (middle != symbol);
  }
  value_ = value - low;
  length_ = high - low;
  if (length_ < kMinLength) renormalise();
  ++model.counts_[symbol];
  if (--model.until_update_ == 0) model.update();
  return symbol;
}

inline std::uint32_t LazArithmeticDecoder::readUpTo19Bits(unsigned bits) {
  length_ >>= bits;
  const std::uint32_t symbol = value_ / length_;
  value_ -= length_ * symbol;
  if (length_ < kMinLength) renormalise();
  return symbol;
}

}  // namespace plumb::io
