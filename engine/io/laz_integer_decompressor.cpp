#include "engine/io/laz_integer_decompressor.h"

#include <algorithm>
#include <cassert>
#include <limits>

namespace plumb::io {

namespace {

unsigned correctorBits(unsigned bits) {
  return bits < 32 ? bits : 32;
}

// The corrector models' sizes: 2^k symbols for k = 1 .. bits_high, 2^bits_high beyond.
std::vector<std::uint32_t> correctorSymbols(unsigned bits, unsigned bits_high) {
  std::vector<std::uint32_t> symbols;
  for (unsigned k = 1; k <= correctorBits(bits); ++k) symbols.push_back(1u << std::min(k, bits_high));
  return symbols;
}

}  // namespace

LazIntegerDecompressor::LazIntegerDecompressor(unsigned bits, unsigned contexts, unsigned bits_high)
    : bits_high_(bits_high),
      corrector_bits_(correctorBits(bits)),
      corrector_range_(bits < 32 ? 1u << bits : 0u),
      corrector_min_(bits < 32 ? -static_cast<std::int32_t>(1u << (bits - 1))
                               : std::numeric_limits<std::int32_t>::min()),
      k_models_(contexts, correctorBits(bits) + 1),
      corrector_models_(correctorSymbols(bits, bits_high)) {
  assert(bits >= 1 && bits <= 32 && "a LAZ integer field has 1 to 32 bits");
  assert(contexts >= 1 && bits_high >= 1 && bits_high <= 11 && "LASzip uses 8 high bits and at least one context");
}

void LazIntegerDecompressor::reset() {
  k_models_.reset();
  k0_model_.reset();
  corrector_models_.reset();
  k_ = 0;
}

// Inlined into decompress(), its only caller: a call and a save of six registers per value cost
// more than the folding after it.
[[gnu::always_inline]] inline std::uint32_t LazIntegerDecompressor::readCorrector(LazArithmeticDecoder& decoder,
                                                                                  unsigned context) {
  k_ = decoder.decodeSymbol(k_models_[context]);
  if (k_ == 0) return decoder.decodeBit(k0_model_);  // c is 0 or 1
  if (k_ >= 32) return static_cast<std::uint32_t>(corrector_min_);

  // The top bits_high_ bits (all of them up to k = bits_high_) with the model of k, the rest raw.
  std::uint32_t c = decoder.decodeSymbol(corrector_models_[k_ - 1]);
  if (k_ > bits_high_) {
    const unsigned low_bits = k_ - bits_high_;
    c = (c << low_bits) | decoder.readBits(low_bits);
  }
  // c is the offset in the 2^k values of the corrector's two intervals: the upper half stands
  // for [2^(k-1) + 1, 2^k], the lower half for [-(2^k - 1), -2^(k-1)]. The comparison is signed,
  // as the reference's, so that corrupt raw bits fold the same way (32-bit wrap-around).
  const bool upper = static_cast<std::int32_t>(c) >= static_cast<std::int32_t>(1u << (k_ - 1));
  c = upper ? c + 1 : c - ((1u << k_) - 1u);
  return c;
}

std::int32_t LazIntegerDecompressor::decompress(LazArithmeticDecoder& decoder, std::int32_t prediction,
                                                unsigned context) {
  // 32-bit wrap-around throughout: a 32-bit field's difference may wrap, and corrupt input must
  // not overflow a signed integer.
  std::uint32_t real = static_cast<std::uint32_t>(prediction) + readCorrector(decoder, context);
  if (static_cast<std::int32_t>(real) < 0) {
    real += corrector_range_;
  } else if (real >= corrector_range_) {
    real -= corrector_range_;
  }
  return static_cast<std::int32_t>(real);
}

}  // namespace plumb::io
