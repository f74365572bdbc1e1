#include "tests/fuzz/mutator.h"

#include <algorithm>
#include <array>
#include <cstring>
#include <string_view>

namespace plumb::fuzz {
namespace {

// A value at which counts, sizes and offsets break: zero, one, or a sign or width boundary of
// 8, 16, 32 or 64-bit integers.
std::uint64_t boundary(Random& random) {
  const std::uint64_t bits = 8u << random.below(4);
  const std::uint64_t top_bit = std::uint64_t{1} << (bits - 1);
  switch (random.below(6)) {
    case 0:
      return 0;
    case 1:
      return 1;
    case 2:
      return top_bit - 1;  // the largest signed
    case 3:
      return top_bit;  // the smallest signed, as unsigned
    case 4:
      return top_bit - 1 + top_bit;  // the largest unsigned
    default:
      return bits == 64 ? 0 : top_bit << 1;  // one past it
  }
}

// What text formats (PLY and PCD headers, ASCII clouds, JSON) choke on.
constexpr std::array<std::string_view, 22> kTokens{
    "0",    "-1",   "1e308", "-1e308", "1e-320", "nan", "inf", "-inf", "4294967296", "18446744073709551616",
    "-0",   "null", "true",  "[",      "]",      "{",   "}",   "\"",   ",",          ":",
    "\"\"", "\n"};

// Each input grows to at most this: bigger inputs only make the run slower.
constexpr std::size_t kMaxBytes = std::size_t{1} << 20;

}  // namespace

Mutator::Mutator(const std::vector<Input>& seeds, std::uint64_t random_seed) : seeds_(seeds), random_(random_seed) {}

const Input& Mutator::next() {
  // Now and then a mutation of the last mutation: some files break only after several changes.
  if (current_.empty() || random_.below(4) != 0) current_ = seeds_[random_.below(seeds_.size())];
  const std::uint64_t count = 1 + random_.below(4);
  for (std::uint64_t i = 0; i < count; ++i) mutateOnce(current_);
  if (current_.size() > kMaxBytes) current_.resize(kMaxBytes);
  return current_;
}

void Mutator::mutateOnce(Input& input) {
  const auto at = [&](std::size_t size) { return static_cast<std::size_t>(random_.below(size + 1)); };
  const auto insert = [&](std::size_t where, const auto* begin, std::size_t size) {
    const auto* first = reinterpret_cast<const std::uint8_t*>(begin);
    input.insert(input.begin() + static_cast<std::ptrdiff_t>(where), first, first + size);
  };
  // Operations that need bytes to work on fall through to an insertion on an empty input.
  switch (input.empty() ? 7 : random_.below(9)) {
    case 0: {  // flip one bit
      input[at(input.size() - 1)] ^= static_cast<std::uint8_t>(1u << random_.below(8));
      break;
    }
    case 1: {  // a little-endian integer of 1, 2, 4 or 8 bytes set to a boundary, or minus it
      const std::size_t width = std::min<std::size_t>(std::size_t{1} << random_.below(4), input.size());
      std::uint64_t value = boundary(random_);
      if (random_.below(2) == 0) value = ~value + 1;
      std::memcpy(input.data() + at(input.size() - width), &value, width);
      break;
    }
    case 2: {  // a token written over the text
      const std::string_view token = kTokens[random_.below(kTokens.size())];
      const std::size_t where = at(input.size());
      const std::size_t over = std::min<std::size_t>(random_.below(8), input.size() - where);
      input.erase(input.begin() + static_cast<std::ptrdiff_t>(where),
                  input.begin() + static_cast<std::ptrdiff_t>(where + over));
      insert(where, token.data(), token.size());
      break;
    }
    case 3: {  // truncate
      input.resize(at(input.size() - 1));
      break;
    }
    case 4: {  // erase a chunk
      const std::size_t where = at(input.size() - 1);
      const std::size_t size = 1 + random_.below(std::min<std::size_t>(input.size() - where, 256));
      input.erase(input.begin() + static_cast<std::ptrdiff_t>(where),
                  input.begin() + static_cast<std::ptrdiff_t>(where + size));
      break;
    }
    case 5: {  // duplicate a chunk somewhere (repeated records, headers, elements)
      const std::size_t from = at(input.size() - 1);
      const std::size_t size = 1 + random_.below(std::min<std::size_t>(input.size() - from, 1024));
      const Input chunk(input.begin() + static_cast<std::ptrdiff_t>(from),
                        input.begin() + static_cast<std::ptrdiff_t>(from + size));
      insert(at(input.size()), chunk.data(), chunk.size());
      break;
    }
    case 6: {  // overwrite a chunk with a copy of another part of the input
      const std::size_t from = at(input.size() - 1);
      const std::size_t to = at(input.size() - 1);
      const std::size_t size = 1 + random_.below(std::min({input.size() - from, input.size() - to, std::size_t{64}}));
      std::memmove(input.data() + to, input.data() + from, size);
      break;
    }
    case 7: {  // insert random bytes
      std::array<std::uint8_t, 16> bytes{};
      for (auto& byte : bytes) byte = static_cast<std::uint8_t>(random_.next());
      insert(at(input.size()), bytes.data(), 1 + random_.below(bytes.size()));
      break;
    }
    default: {  // splice: this input's head, another seed's tail
      const Input& other = seeds_[random_.below(seeds_.size())];
      const std::size_t head = at(input.size());
      const std::size_t tail_from = at(other.size());
      input.resize(head);
      input.insert(input.end(), other.begin() + static_cast<std::ptrdiff_t>(tail_from), other.end());
      break;
    }
  }
}

}  // namespace plumb::fuzz
