// LZF decompression (liblzf's format; see lzf.h), written from the format description:
//
//   1. Read a control byte.
//   2. Literal run (control < 32): check that control + 1 bytes remain in the input and fit in
//      the output, then copy them.
//   3. Back reference: read the length (and its extra byte when the 3-bit length is 7) and the
//      low offset byte, check the reference lies within the output written so far and the copy
//      fits, then copy forward byte by byte when source and destination overlap.
//   4. Repeat until the input is consumed.

#include "engine/io/lzf.h"

#include <cstdint>
#include <cstring>

namespace plumb::io {
namespace {

constexpr unsigned kMaxLiteralControl = 31;  // controls 0..31 are literal runs of 1..32 bytes
constexpr unsigned kLongLength = 7;          // a 3-bit length of 7 takes an extra length byte

}  // namespace

bool lzfDecompress(std::span<const std::byte> in, std::span<std::byte> out, std::size_t& written) {
  std::size_t ip = 0;
  std::size_t op = 0;
  written = 0;
  // A malformed chunk stops decoding; `written` keeps what was decoded before it.
  const auto fail = [&] {
    written = op;
    return false;
  };
  while (ip < in.size()) {
    const unsigned control = std::to_integer<unsigned>(in[ip++]);
    if (control <= kMaxLiteralControl) {
      const std::size_t length = control + 1;
      if (length > in.size() - ip || length > out.size() - op) return fail();
      std::memcpy(out.data() + op, in.data() + ip, length);
      ip += length;
      op += length;
      continue;
    }
    std::size_t length = (control >> 5) + 2;
    if ((control >> 5) == kLongLength) {
      if (ip >= in.size()) return fail();
      length += std::to_integer<std::size_t>(in[ip++]);
    }
    if (ip >= in.size()) return fail();
    const std::size_t distance = ((std::size_t{control} & 0x1f) << 8) + std::to_integer<std::size_t>(in[ip++]) + 1;
    if (distance > op || length > out.size() - op) return fail();
    std::byte* destination = out.data() + op;
    const std::byte* source = destination - distance;
    if (distance >= length) {
      std::memcpy(destination, source, length);
    } else {
      // Overlap: each byte may be one this copy has just written (a repeated pattern).
      for (std::size_t i = 0; i < length; ++i) destination[i] = source[i];
    }
    op += length;
  }
  written = op;
  return true;
}

}  // namespace plumb::io
