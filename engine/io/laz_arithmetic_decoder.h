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
//     above 8 symbols a look-up table (finer than the reference's) narrows the search before a
//     bisection;
//   - raw bits, 1 to 32, of uniform probability.
// Every operation is bit-exact with the reference: a decoded stream only matches when each
// multiply, shift and truncation is the same.
//
// Corrupt input never reads outside the models' arrays: it decodes garbage until the chunk's
// bytes run out, and LazByteInput then throws plumb::Error with the file and the byte offset.

#include <algorithm>
#include <bit>
#include <cassert>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
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

  // Bytes buffered beyond the next one's position; peekFour() needs 4.
  std::size_t buffered() const { return filled_ - at_; }
  // The next 4 bytes as a big-endian number, not consumed; skip() consumes them.
  std::uint32_t peekFour() const {
    const std::uint8_t* p = buffer_.get() + at_;
    return (std::uint32_t{p[0]} << 24) | (std::uint32_t{p[1]} << 16) | (std::uint32_t{p[2]} << 8) | p[3];
  }
  void skip(std::size_t bytes) { at_ += bytes; }

  // File offset of the byte next() returns next.
  std::uint64_t offset() const { return buffer_start_ + at_; }
  std::uint64_t end() const { return end_; }
  const std::string& what() const { return what_; }
  const FileSource& source() const { return source_; }

 private:
  void refill();

  FileSource& source_;
  std::unique_ptr<std::uint8_t[]> buffer_;  // not zeroed: a small file's chunk needs a few bytes of it
  std::size_t capacity_ = 0;
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
// Its arrays lie in one block; a model just reset copies the block that every model of its size
// has then (resetBlock() in the .cpp), made once for the process.
class LazSymbolModel {
 public:
  explicit LazSymbolModel(std::uint32_t symbols);
  LazSymbolModel(const LazSymbolModel& other);
  LazSymbolModel(LazSymbolModel&&) noexcept = default;
  LazSymbolModel& operator=(const LazSymbolModel& other) { return *this = LazSymbolModel(other); }
  LazSymbolModel& operator=(LazSymbolModel&&) noexcept = default;
  ~LazSymbolModel() = default;

  std::uint32_t symbols() const { return symbols_; }
  void reset();

 private:
  friend class LazArithmeticDecoder;
  void update();
  void allocate();  // block_ and the pointers into it, for symbols_ and table_size_
  std::size_t blockSize() const;

  std::uint32_t symbols_;
  std::uint32_t last_symbol_;
  std::uint32_t table_size_ = 0, table_shift_ = 0;  // table_size_ 0: no look-up table
  std::uint32_t total_count_ = 0, update_cycle_ = 0, until_update_ = 0;
  std::unique_ptr<std::uint32_t[]> block_;
  std::uint32_t* distribution_ = nullptr;       // symbols_ + 1: cumulative, scaled to 2^15, and a padding
  std::uint32_t* counts_ = nullptr;             // symbols_
  std::uint32_t* table_ = nullptr;              // table_size_ + 2: first symbol per slice of the range
  const std::uint32_t* reset_block_ = nullptr;  // the block as reset() leaves it, shared
};

// Symbol models made and reset when first used in a chunk, not when the chunk begins: a coder
// holds many more models than a chunk uses (an integer field of 32 bits has a corrector model of
// up to 256 symbols for each of its 32 corrector widths), and resetting each is a pass over its
// symbols. The decoded values are the same: a model's first use sees the state reset() gives.
class LazModelSet {
 public:
  // One model of symbols[i] values per slot.
  explicit LazModelSet(std::vector<std::uint32_t> symbols);
  LazModelSet(std::size_t count, std::uint32_t symbols) : LazModelSet(std::vector<std::uint32_t>(count, symbols)) {}

  // Every model back to its reset state before its next use (as at the start of a chunk).
  void reset() { ++generation_; }

  LazSymbolModel& operator[](std::size_t i) {
    assert(i < slots_.size() && "a model beyond the set's");
    Slot& slot = slots_[i];
    if (slot.generation != generation_) [[unlikely]]
      prepare(slot, i);
    return *slot.model;
  }

 private:
  struct Slot {
    std::optional<LazSymbolModel> model;
    std::uint64_t generation = 0;  // of the last reset; 0: not made yet
  };
  void prepare(Slot& slot, std::size_t i);

  std::vector<Slot> slots_;
  std::vector<std::uint32_t> symbols_;
  std::uint64_t generation_ = 1;
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
  const std::uint32_t length = length_;
  if (length != 0 && input_.buffered() >= 4) [[likely]] {
    const unsigned bits = static_cast<unsigned>(std::countl_zero(length)) & ~7u;  // 0 at >= 2^24
    value_ =
        static_cast<std::uint32_t>((std::uint64_t{value_} << bits) | (std::uint64_t{input_.peekFour()} >> (32 - bits)));
    length_ = static_cast<std::uint32_t>(std::uint64_t{length} << bits);
    input_.skip(bits >> 3);
    return;
  }
  if (length >= kMinLength) return;
  std::uint32_t value = value_;
  std::uint32_t shifted = length;
  do {
    value = (value << 8) | input_.next();
    shifted <<= 8;
  } while (shifted < kMinLength);
  value_ = value;
  length_ = shifted;
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
  renormalise();
  if (--model.until_update_ == 0) model.update();
  return bit;
}

inline std::uint32_t LazArithmeticDecoder::decodeSymbol(LazSymbolModel& model) {
  const std::uint32_t* const distribution = model.distribution_;
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
    const std::uint32_t next = distribution[symbol + 1] * length;  // the padding after the last
    high = symbol != model.last_symbol_ ? next : high;
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
  renormalise();
  ++model.counts_[symbol];
  if (--model.until_update_ == 0) model.update();
  return symbol;
}

inline std::uint32_t LazArithmeticDecoder::readUpTo19Bits(unsigned bits) {
  length_ >>= bits;
  const std::uint32_t symbol = value_ / length_;
  value_ -= length_ * symbol;
  renormalise();
  return symbol;
}

}  // namespace plumb::io
