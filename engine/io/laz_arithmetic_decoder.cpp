#include "engine/io/laz_arithmetic_decoder.h"

#include <algorithm>
#include <array>
#include <cassert>
#include <cstring>
#include <mutex>

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
  if (capacity_ < bytes) {
    buffer_.reset(new std::uint8_t[bytes]);
    capacity_ = bytes;
  }
  source_.seek(at);
  source_.readExactly(std::as_writable_bytes(std::span(buffer_.get(), bytes)), what_);
  buffer_start_ = at;
  at_ = 0;
  filled_ = bytes;
}

void LazByteInput::read(std::span<std::byte> out) {
  std::size_t done = 0;
  while (done < out.size()) {
    if (at_ == filled_) refill();
    const std::size_t take = std::min(out.size() - done, filled_ - at_);
    std::memcpy(out.data() + done, buffer_.get() + at_, take);
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

namespace {

// A symbol model's look-up table: one entry per 2^shift of the 2^15 range, at least as many as
// symbols (and 32), so that a probable symbol holds its slices alone and the bisection after the
// look-up seldom runs. (The reference's table has about a quarter as many entries; a table only
// narrows the search, so its size cannot change what is decoded. 4 times finer: 11 % faster.)
struct TableShape {
  std::uint32_t size = 0, shift = 0;  // size 0: no table, a bisection on the products
};

TableShape tableShape(std::uint32_t symbols) {
  if (symbols <= kSymbolsWithoutTable) return {};
  std::uint32_t bits = 5;
  while ((1u << bits) < symbols) ++bits;
  return {1u << bits, kSymbolLengthShift - bits};
}

// A model's block: the distribution (symbols + 1), the counts (symbols), the table (size + 2).
std::size_t blockSizeOf(std::uint32_t symbols, TableShape table) {
  return 2 * std::size_t{symbols} + 1 + (table.size != 0 ? table.size + 2 : 0);
}

// The cumulative distribution of `counts` (summing to `total`, at most 2^15) scaled to 2^15, and
// the look-up table over it: table[t] is the largest symbol whose cumulative value lies below
// slice t of the range.
void fillDistribution(const std::uint32_t* counts, std::uint32_t symbols, std::uint32_t total, TableShape table_shape,
                      std::uint32_t* distribution, std::uint32_t* table) {
  // scale * sum stays below 2^31.
  const std::uint32_t scale = 0x80000000u / total;
  std::uint32_t sum = 0;
  if (table_shape.size == 0) {
    for (std::uint32_t k = 0; k < symbols; ++k) {
      distribution[k] = (scale * sum) >> (31 - kSymbolLengthShift);
      sum += counts[k];
    }
    return;
  }
  std::uint32_t slice = 0;
  for (std::uint32_t k = 0; k < symbols; ++k) {
    distribution[k] = (scale * sum) >> (31 - kSymbolLengthShift);
    sum += counts[k];
    const std::uint32_t reached = distribution[k] >> table_shape.shift;
    while (slice < reached) table[++slice] = k - 1;
  }
  table[0] = 0;
  while (slice <= table_shape.size) table[++slice] = symbols - 1;
}

// The block of a model of `symbols` symbols just reset: every count 1, and the distribution and
// table they give. It is the same for every model of that size, so it is made once per size for
// the process and copied; computing it at each reset was a tenth of the decoding of a
// thousand-point file, whose coders make and reset hundreds of models of up to 256 symbols for
// its one chunk. Thread-safe: chunks are decoded in parallel.
const std::uint32_t* resetBlock(std::uint32_t symbols) {
  static std::mutex mutex;
  static std::array<std::unique_ptr<std::uint32_t[]>, kMaxSymbols + 1> blocks;
  const std::lock_guard lock(mutex);
  std::unique_ptr<std::uint32_t[]>& block = blocks[symbols];
  if (!block) {
    const TableShape table_shape = tableShape(symbols);
    block = std::make_unique<std::uint32_t[]>(blockSizeOf(symbols, table_shape));  // the padding 0
    std::uint32_t* const distribution = block.get();
    std::uint32_t* const counts = distribution + symbols + 1;
    std::fill(counts, counts + symbols, 1u);
    fillDistribution(counts, symbols, symbols, table_shape, distribution, counts + symbols);
  }
  return block.get();
}

}  // namespace

LazSymbolModel::LazSymbolModel(std::uint32_t symbols) : symbols_(symbols), last_symbol_(symbols - 1) {
  assert(symbols >= 2 && symbols <= kMaxSymbols && "a LAZ symbol model has 2 to 2048 symbols");
  const TableShape table_shape = tableShape(symbols_);
  table_size_ = table_shape.size;
  table_shift_ = table_shape.shift;
  reset_block_ = resetBlock(symbols_);
  allocate();
  reset();  // copies: total_count_ is 0 until then, never a reset model's symbols_
}

LazSymbolModel::LazSymbolModel(const LazSymbolModel& other)
    : symbols_(other.symbols_),
      last_symbol_(other.last_symbol_),
      table_size_(other.table_size_),
      table_shift_(other.table_shift_),
      total_count_(other.total_count_),
      update_cycle_(other.update_cycle_),
      until_update_(other.until_update_),
      reset_block_(other.reset_block_) {
  allocate();
  std::memcpy(block_.get(), other.block_.get(), blockSize() * sizeof(std::uint32_t));
}

std::size_t LazSymbolModel::blockSize() const {
  return blockSizeOf(symbols_, {table_size_, table_shift_});
}

void LazSymbolModel::allocate() {
  block_.reset(new std::uint32_t[blockSize()]);  // not zeroed: a copy fills it
  distribution_ = block_.get();
  counts_ = distribution_ + symbols_ + 1;
  table_ = table_size_ != 0 ? counts_ + symbols_ : nullptr;
}

void LazSymbolModel::reset() {
  // Nothing decoded since the last reset: the state is the reset one already (a decode counts
  // down until_update_, an update raises total_count_ above symbols_). Spares the copy for the
  // models a chunk never uses and for a coder's first chunk.
  if (total_count_ == symbols_ && until_update_ == update_cycle_) return;
  std::memcpy(block_.get(), reset_block_, blockSize() * sizeof(std::uint32_t));
  total_count_ = symbols_;  // the counts' sum
  update_cycle_ = until_update_ = (symbols_ + 6) >> 1;
}

void LazSymbolModel::update() {
  total_count_ += update_cycle_;
  if (total_count_ > kSymbolMaxCount) {
    total_count_ = 0;
    for (std::uint32_t k = 0; k < symbols_; ++k) {
      counts_[k] = (counts_[k] + 1) >> 1;
      total_count_ += counts_[k];
    }
  }
  // total_count_ is the sum of the counts (each decoded symbol added one, update_cycle_ of them
  // since the last update), at most 2^15.
  fillDistribution(counts_, symbols_, total_count_, {table_size_, table_shift_}, distribution_, table_);
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
