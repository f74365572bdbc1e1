#pragma once
// Reading and writing numbers at byte positions of file data, in a given byte order: the one
// place the binary formats (PLY, LAS, PCD) take their scalars from.

#include <algorithm>
#include <array>
#include <bit>
#include <cstddef>
#include <cstring>

namespace plumb::io {

// The T stored at `p`, its bytes reversed first when `swap` is set.
template <typename T>
T loadBytes(const std::byte* p, bool swap) {
  std::array<std::byte, sizeof(T)> bytes;
  std::memcpy(bytes.data(), p, sizeof(T));
  if (swap) std::reverse(bytes.begin(), bytes.end());
  return std::bit_cast<T>(bytes);
}

// The little-endian T stored at `p`, on any host.
template <typename T>
T loadLittleEndian(const std::byte* p) {
  return loadBytes<T>(p, std::endian::native != std::endian::little);
}

// Stores the little-endian bytes of `value` at `out`; returns the position after them.
template <typename T>
std::byte* packLittleEndian(std::byte* out, T value) {
  auto bytes = std::bit_cast<std::array<std::byte, sizeof(T)>>(value);
  if constexpr (std::endian::native != std::endian::little) std::reverse(bytes.begin(), bytes.end());
  std::memcpy(out, bytes.data(), sizeof(T));
  return out + sizeof(T);
}

}  // namespace plumb::io
