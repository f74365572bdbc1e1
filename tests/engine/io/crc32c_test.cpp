// CRC-32C (engine/io/crc32c.h) against the check values of its definition.
#include "engine/io/crc32c.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace plumb::io {
namespace {

std::uint32_t crcOf(const std::string& text) {
  return crc32c(std::as_bytes(std::span(text.data(), text.size())));
}

TEST(Crc32c, MatchesTheCheckValuesOfTheCastagnoliPolynomial) {
  // The catalogue's check value (CRC-32/ISCSI) and RFC 3720's test patterns (iSCSI, B.4).
  EXPECT_EQ(crcOf("123456789"), 0xE3069283u);
  EXPECT_EQ(crcOf(std::string(32, '\0')), 0x8A9136AAu);
  EXPECT_EQ(crcOf(std::string(32, '\xFF')), 0x62A8AB43u);
  std::string ascending;
  for (int i = 0; i < 32; ++i) ascending += static_cast<char>(i);
  EXPECT_EQ(crcOf(ascending), 0x46DD794Eu);
  EXPECT_EQ(crcOf(""), 0u);
}

TEST(Crc32c, EveryLengthAgreesWithTheBytewiseDefinition) {
  // The eight-byte steps and the byte-wise tail meet at every length and alignment.
  std::string data;
  for (int i = 0; i < 100; ++i) data += static_cast<char>(i * 37 + 11);
  for (std::size_t start = 0; start < 8; ++start) {
    for (std::size_t length = 0; start + length <= data.size(); ++length) {
      std::uint32_t crc = 0xFFFFFFFFu;
      for (std::size_t i = start; i < start + length; ++i) {
        crc ^= static_cast<unsigned char>(data[i]);
        for (int bit = 0; bit < 8; ++bit) crc = (crc >> 1) ^ ((crc & 1u) != 0 ? 0x82F63B78u : 0u);
      }
      EXPECT_EQ(crcOf(data.substr(start, length)), crc ^ 0xFFFFFFFFu) << start << " " << length;
    }
  }
}

}  // namespace
}  // namespace plumb::io
