#include "engine/io/laz_arithmetic_decoder.h"

#include <algorithm>
#include <cassert>
#include <cstring>

namespace plumb::io {
namespace {

constexpr std::uint32_t kMaxLength = 0xFFFFFFFFu;

// Bit models: the probability of 0 in 13 bits (kBitLengthShift); counts are halved beyond 2^13.
constexpr unsigned kBitLengthShift = LazArithmeticDecoder::kBitLengthShift;
constexpr std::uint32_t kBitMaxCount = 1u << kBitLengthShift;
constexpr std::uint32_t kBitMaxUpdateCycle = 64;

// Symbol models: the distribution in 15 bits (kSymbolLengthShift); counts are halved beyond 2^15.
constexpr unsigned kSymbolLengthShift = LazArithmeticDecoder::kSymbolLengthShift;
constexpr std::uint32_t kSymbolMaxCount = 1u << kSymbolLengthShift;
constexpr std::uint32_t kMaxSymbols = 1u << 11;
constexpr std::uint32_t kSymbolsWithoutTable = 8;  // fewer: a bisection on the products

// Bytes read from the file at a time.
constexpr std::size_t kInputBlockBytes = std::size_t{64} << 10;

}  // namespace

// ---- LazByteInput ----------------------------------------------------------------------------

void LazByteInput::reset(std::uint64_t begin, std::uint64_t end, std::string what) {
  assert(begin <= end && end <= source_.size() && "a LAZ stretch must lie inside the file");
  buffer_start_ = begin;
  at_ = filled_ = 0;
  end_ = end;
  what_ = std::move(what);
}

void LazByteInput::refill() {
  const std::uint64_t at = offset();
  if (at >= end_) {
    throw source_.errorAt(end_, "truncated or corrupt LAZ data: " + what_ +
                                    " needs more bytes than it has (its compressed data ends here "
                                    "before its points are decoded)");
  }
  const std::size_t bytes = static_cast<std::size_t>(std::min<std::uint64_t>(kInputBlockBytes, end_ - at));
  if (buffer_.size() < bytes) buffer_.resize(kInputBlockBytes);
  source_.seek(at);
  source_.readExactly(std::as_writable_bytes(std::span(buffer_.data(), bytes)), what_);
  buffer_start_ = at;
  at_ = 0;
  filled_ = bytes;
}

void LazByteInput::read(std::span<std::byte> out) {
  std::size_t done = 0;
  while (done < out.size()) {
    if (at_ == filled_) refill();
    const std::size_t take = std::min(out.size() - done, filled_ - at_);
    std::memcpy(out.data() + done, buffer_.data() + at_, take);
    at_ += take;
    done += take;
  }
}

// ---- The models ------------------------------------------------------------------------------

void LazBitModel::reset() {
  bit_0_count_ = 1;
  bit_count_ = 2;
  bit_0_probability_ = 1u << (kBitLengthShift - 1);
  update_cycle_ = until_update_ = 4;  // adapt quickly at first
}

void LazBitModel::update() {
  bit_count_ += update_cycle_;
  if (bit_count_ > kBitMaxCount) {
    bit_count_ = (bit_count_ + 1) >> 1;
    bit_0_count_ = (bit_0_count_ + 1) >> 1;
    // Keep some probability for 1: a model sure of 0 could not code a 1 at all.
    if (bit_0_count_ == bit_count_) ++bit_count_;
  }
  const std::uint32_t scale = 0x80000000u / bit_count_;
  bit_0_probability_ = (bit_0_count_ * scale) >> (31 - kBitLengthShift);
  update_cycle_ = std::min((5 * update_cycle_) >> 2, kBitMaxUpdateCycle);
  until_update_ = update_cycle_;
}

LazSymbolModel::LazSymbolModel(std::uint32_t symbols) : symbols_(symbols), last_symbol_(symbols - 1) {
  assert(symbols >= 2 && symbols <= kMaxSymbols && "a LAZ symbol model has 2 to 2048 symbols");
  if (symbols_ > kSymbolsWithoutTable) {
    // One table entry per 2^table_shift_ of the 2^15 range, at least as many as symbols (and 32):
    // a probable symbol then holds its slices alone and the bisection after the look-up seldom
    // runs. (The reference's table has about a quarter as many entries; a table only narrows the
    // search, so its size cannot change what is decoded. 4 times finer: 11 % faster.)
    std::uint32_t table_bits = 5;
    while ((1u << table_bits) < symbols_) ++table_bits;
    table_size_ = 1u << table_bits;
    table_shift_ = kSymbolLengthShift - table_bits;
    table_.resize(table_size_ + 2);
  }
  distribution_.resize(symbols_ + 1);  // and a padding entry, read and not used after the last
  counts_.resize(symbols_);
  reset();
}

void LazSymbolModel::reset() {
  // Nothing decoded since the last reset: the state is the reset one already (a decode counts
  // down until_update_, an update raises total_count_ above symbols_). Spares a pass over the
  // symbols for the models a chunk never uses and for a coder's first chunk.
  if (total_count_ == symbols_ && until_update_ == update_cycle_) return;
  total_count_ = 0;
  update_cycle_ = symbols_;
  std::fill(counts_.begin(), counts_.end(), 1u);
  update();
  update_cycle_ = until_update_ = (symbols_ + 6) >> 1;
}

void LazSymbolModel::update() {
  total_count_ += update_cycle_;
  if (total_count_ > kSymbolMaxCount) {
    total_count_ = 0;
    for (std::uint32_t& count : counts_) {
      count = (count + 1) >> 1;
      total_count_ += count;
    }
  }
  // total_count_ is the sum of the counts (each decoded symbol added one, update_cycle_ of them
  // since the last update), at most 2^15: scale * sum stays below 2^31.
  const std::uint32_t scale = 0x80000000u / total_count_;
  std::uint32_t sum = 0;
  if (table_size_ == 0) {
    for (std::uint32_t k = 0; k < symbols_; ++k) {
      distribution_[k] = (scale * sum) >> (31 - kSymbolLengthShift);
      sum += counts_[k];
    }
  } else {
    // table_[t]: the largest symbol whose cumulative value lies below slice t of the range.
    std::uint32_t slice = 0;
    for (std::uint32_t k = 0; k < symbols_; ++k) {
      distribution_[k] = (scale * sum) >> (31 - kSymbolLengthShift);
      sum += counts_[k];
      const std::uint32_t reached = distribution_[k] >> table_shift_;
      while (slice < reached) table_[++slice] = k - 1;
    }
    table_[0] = 0;
    while (slice <= table_size_) table_[++slice] = symbols_ - 1;
  }
  update_cycle_ = std::min((5 * update_cycle_) >> 2, (symbols_ + 6) << 3);
  until_update_ = update_cycle_;
}

LazModelSet::LazModelSet(std::vector<std::uint32_t> symbols) : slots_(symbols.size()), symbols_(std::move(symbols)) {}

void LazModelSet::prepare(Slot& slot, std::size_t i) {
  if (slot.model) {
    slot.model->reset();
  } else {
    slot.model.emplace(symbols_[i]);
  }
  slot.generation = generation_;
}

// ---- The decoder -----------------------------------------------------------------------------

void LazArithmeticDecoder::start() {
  length_ = kMaxLength;
  value_ = 0;
  for (int i = 0; i < 4; ++i) value_ = (value_ << 8) | input_.next();
}

std::uint32_t LazArithmeticDecoder::readBits(unsigned bits) {
  assert(bits >= 1 && bits <= 32 && "readBits takes 1 to 32 bits");
  if (bits > 19) {
    // Beyond 19 bits the shifted length would leave too little precision: 16 bits first.
    const std::uint32_t low = readShort();
    const std::uint32_t high = readBits(bits - 16);
    return (high << 16) | low;
  }
  return readUpTo19Bits(bits);
}

std::uint16_t LazArithmeticDecoder::readShort() {
  return static_cast<std::uint16_t>(readUpTo19Bits(16));
}

std::uint32_t LazArithmeticDecoder::readInt() {
  const std::uint32_t low = readShort();
  const std::uint32_t high = readShort();
  return (high << 16) | low;
}

std::uint64_t LazArithmeticDecoder::readInt64() {
  const std::uint64_t low = readInt();
  const std::uint64_t high = readInt();
  return (high << 32) | low;
}

}  // namespace plumb::io
