#pragma once
// A LAZ range encoder for tests: the encoding side of the FastAC coder that LASzip adapts
// (A. Said, "Introduction to Arithmetic Coding: Theory and Practice", HP Labs HPL-2004-76; the
// LASzip reference implementation, src/arithmeticencoder.cpp and src/integercompressor.cpp, read,
// not copied), with its own models. Tests encode values with it and check that Plumb's decoder
// (engine/io/laz_arithmetic_decoder.h) gives them back, and write LAZ chunk tables that no file
// in ../shared/data has (variable chunks).
//
// The models here restate the reference's update rules independently of the decoder's: a round
// trip passes only when both sides adapt identically.

#include <algorithm>
#include <bit>
#include <cassert>
#include <cstdint>
#include <vector>

namespace plumb::test {

class TestBitModel {
 public:
  std::uint32_t probability0 = 1u << 12;  // of a 0, in 13 bits

  void counted(std::uint32_t bit) {
    if (bit == 0) ++zeros_;
    if (--until_update_ > 0) return;
    total_ += cycle_;
    if (total_ > (1u << 13)) {
      total_ = (total_ + 1) / 2;
      zeros_ = (zeros_ + 1) / 2;
      if (zeros_ == total_) ++total_;
    }
    probability0 = (zeros_ * (0x80000000u / total_)) >> 18;
    cycle_ = std::min((5 * cycle_) / 4, 64u);
    until_update_ = cycle_;
  }

 private:
  std::uint32_t zeros_ = 1, total_ = 2, cycle_ = 4, until_update_ = 4;
};

class TestSymbolModel {
 public:
  explicit TestSymbolModel(std::uint32_t symbols) : counts_(symbols, 1), cumulative(symbols) {
    cycle_ = symbols;
    recompute();
    cycle_ = until_update_ = (symbols + 6) / 2;
  }

  std::uint32_t symbols() const { return static_cast<std::uint32_t>(counts_.size()); }

  void counted(std::uint32_t symbol) {
    ++counts_[symbol];
    if (--until_update_ == 0) recompute();
  }

 private:
  void recompute() {
    total_ += cycle_;
    if (total_ > (1u << 15)) {
      total_ = 0;
      for (std::uint32_t& count : counts_) total_ += count = (count + 1) / 2;
    }
    const std::uint32_t scale = 0x80000000u / total_;
    std::uint32_t below = 0;
    for (std::size_t k = 0; k < counts_.size(); ++k) {
      cumulative[k] = (scale * below) >> 16;
      below += counts_[k];
    }
    cycle_ = std::min((5 * cycle_) / 4, (symbols() + 6) * 8);
    until_update_ = cycle_;
  }

  std::vector<std::uint32_t> counts_;
  std::uint32_t total_ = 0, cycle_ = 0, until_update_ = 0;

 public:
  std::vector<std::uint32_t> cumulative;  // scaled to 2^15
};

class TestRangeEncoder {
 public:
  void encodeBit(TestBitModel& model, std::uint32_t bit) {
    const std::uint32_t bound = model.probability0 * (length_ >> 13);
    if (bit == 0) {
      length_ = bound;
    } else {
      add(bound);
      length_ -= bound;
    }
    if (length_ < kMinLength) renormalise();
    model.counted(bit);
  }

  void encodeSymbol(TestSymbolModel& model, std::uint32_t symbol) {
    assert(symbol < model.symbols());
    if (symbol + 1 == model.symbols()) {
      const std::uint32_t low = model.cumulative[symbol] * (length_ >> 15);
      add(low);
      length_ -= low;
    } else {
      length_ >>= 15;
      const std::uint32_t low = model.cumulative[symbol] * length_;
      add(low);
      length_ = model.cumulative[symbol + 1] * length_ - low;
    }
    if (length_ < kMinLength) renormalise();
    model.counted(symbol);
  }

  void writeBits(unsigned bits, std::uint32_t value) {
    assert(bits >= 1 && bits <= 32 && (bits == 32 || value < (1u << bits)));
    if (bits > 19) {
      writeBits(16, value & 0xFFFF);
      value >>= 16;
      bits -= 16;
    }
    length_ >>= bits;
    add(value * length_);
    if (length_ < kMinLength) renormalise();
  }

  // The coded bytes, with the final ones the decoder reads.
  std::vector<std::uint8_t> finish() {
    bool three_zeros = true;
    if (length_ > 2 * kMinLength) {
      add(kMinLength);
      length_ = kMinLength >> 1;
    } else {
      add(kMinLength >> 1);
      length_ = kMinLength >> 9;
      three_zeros = false;
    }
    renormalise();
    out_.insert(out_.end(), three_zeros ? 3 : 2, 0);
    return out_;
  }

 private:
  static constexpr std::uint32_t kMinLength = 1u << 24;

  // base += value, carrying into the bytes already written.
  void add(std::uint32_t value) {
    const std::uint32_t before = base_;
    base_ += value;
    if (base_ >= before) return;
    std::size_t i = out_.size();
    while (i > 0 && out_[i - 1] == 0xFF) out_[--i] = 0;
    assert(i > 0 && "a carry out of the first byte: the interval left [0, 2^32)");
    ++out_[i - 1];
  }

  void renormalise() {
    do {
      out_.push_back(static_cast<std::uint8_t>(base_ >> 24));
      base_ <<= 8;
      length_ <<= 8;
    } while (length_ < kMinLength);
  }

  std::uint32_t base_ = 0, length_ = 0xFFFFFFFFu;
  std::vector<std::uint8_t> out_;
};

// The integer corrector coding of LazIntegerDecompressor, encoding side.
class TestIntegerCompressor {
 public:
  TestIntegerCompressor(unsigned bits, unsigned contexts, unsigned bits_high = 8)
      : bits_(bits), bits_high_(bits_high), k0_() {
    const unsigned corrector_bits = bits < 32 ? bits : 32;
    for (unsigned i = 0; i < contexts; ++i) k_models_.emplace_back(corrector_bits + 1);
    for (unsigned k = 1; k <= corrector_bits; ++k) correctors_.emplace_back(1u << std::min(k, bits_high));
  }

  void compress(TestRangeEncoder& encoder, std::int32_t prediction, std::int32_t value, unsigned context) {
    std::int64_t c = static_cast<std::int64_t>(value) - prediction;
    if (bits_ < 32) {
      // Fold into [-2^(bits-1), 2^(bits-1) - 1].
      const std::int64_t range = std::int64_t{1} << bits_;
      if (c < -range / 2) c += range;
      if (c > range / 2 - 1) c -= range;
    } else {
      c = static_cast<std::int32_t>(static_cast<std::uint32_t>(c));  // 32-bit wrap
    }
    const std::uint64_t magnitude = c <= 0 ? static_cast<std::uint64_t>(-c) : static_cast<std::uint64_t>(c - 1);
    const auto k = static_cast<unsigned>(std::bit_width(magnitude));
    encoder.encodeSymbol(k_models_[context], k);
    if (k == 0) {
      encoder.encodeBit(k0_, static_cast<std::uint32_t>(c));
      return;
    }
    if (k == 32) return;  // c is -2^31
    // The offset in the 2^k values of c's two intervals.
    const auto offset = static_cast<std::uint32_t>(c < 0 ? c + (std::int64_t{1} << k) - 1 : c - 1);
    if (k <= bits_high_) {
      encoder.encodeSymbol(correctors_[k - 1], offset);
    } else {
      const unsigned low_bits = k - bits_high_;
      encoder.encodeSymbol(correctors_[k - 1], offset >> low_bits);
      encoder.writeBits(low_bits, offset & ((1u << low_bits) - 1));
    }
  }

 private:
  unsigned bits_, bits_high_;
  std::vector<TestSymbolModel> k_models_;
  TestBitModel k0_;
  std::vector<TestSymbolModel> correctors_;
};

}  // namespace plumb::test
