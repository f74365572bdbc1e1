// libFuzzer target for the LZF decompressor (PCD's binary_compressed data): arbitrary blocks into
// a bounded output. Run by scripts/fuzz, and replayed in the test suite (fuzz_replay_main.cpp).

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "engine/io/lzf.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 2) return 0;
  // The first two bytes choose the output size, as a PCD header would declare it.
  const std::size_t out_size = (std::size_t{data[0]} << 8 | data[1]) % 65536;
  std::vector<std::byte> out(out_size);
  std::size_t written = 0;
  const auto in = std::as_bytes(std::span(data + 2, size - 2));
  if (plumb::io::lzfDecompress(in, out, written) && written > out.size()) __builtin_trap();
  return 0;
}
