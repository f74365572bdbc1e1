#pragma once
// CRC-32C (Castagnoli: reflected polynomial 0x82F63B78, initial value and final XOR 0xFFFFFFFF),
// the checksum of every E57 page (ASTM E2807, section 8.2). Debian 12 packages no CRC-32C
// library (zlib has CRC-32 only), so it is computed here: slicing by eight, one table lookup per
// byte in eight independent lanes.

#include <cstddef>
#include <cstdint>
#include <span>

namespace plumb::io {

// The CRC-32C of `bytes`.
std::uint32_t crc32c(std::span<const std::byte> bytes);

}  // namespace plumb::io
