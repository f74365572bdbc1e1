#include "engine/io/e57_file.h"

#include <algorithm>
#include <array>
#include <cstring>

#include "engine/io/byte_order.h"
#include "engine/io/crc32c.h"

namespace plumb::io {
namespace {

// The file header, section 8.3 (table 2): all little-endian.
constexpr std::size_t kHeaderBytes = 48;
constexpr std::size_t kVersionMajorAt = 8;
constexpr std::size_t kVersionMinorAt = 12;
constexpr std::size_t kPhysicalLengthAt = 16;
constexpr std::size_t kXmlOffsetAt = 24;
constexpr std::size_t kXmlLengthAt = 32;
constexpr std::size_t kPageSizeAt = 40;

#ifdef FUZZING_BUILD_MODE_UNSAFE_FOR_PRODUCTION
constexpr bool kEnforceChecksums = false;  // fuzz builds (CMakeLists.txt): mutations must reach the decoders
#else
constexpr bool kEnforceChecksums = true;
#endif

}  // namespace

E57File::E57File(const std::string& path) : source_(path) {
  if (source_.size() < kPageBytes) {
    throw source_.errorAt(0, "not an E57 file: " + std::to_string(source_.size()) +
                                 " bytes, less than the one page (1024 bytes) every E57 file has");
  }
  const std::span<const std::byte> first = page(0);
  if (std::memcmp(first.data(), "ASTM-E57", 8) != 0) throw errorAt(0, "not an E57 file: no ASTM-E57 signature");
  version_major_ = loadLittleEndian<std::uint32_t>(first.data() + kVersionMajorAt);
  version_minor_ = loadLittleEndian<std::uint32_t>(first.data() + kVersionMinorAt);
  const auto physical_length = loadLittleEndian<std::uint64_t>(first.data() + kPhysicalLengthAt);
  xml_offset_ = loadLittleEndian<std::uint64_t>(first.data() + kXmlOffsetAt);
  xml_length_ = loadLittleEndian<std::uint64_t>(first.data() + kXmlLengthAt);
  const auto page_size = loadLittleEndian<std::uint64_t>(first.data() + kPageSizeAt);
  if (version_major_ != 1) {
    throw errorAt(kVersionMajorAt, "E57 version " + std::to_string(version_major_) + "." +
                                       std::to_string(version_minor_) + ": only version 1 is read");
  }
  if (page_size != kPageBytes) {
    throw errorAt(kPageSizeAt, "page size " + std::to_string(page_size) + ", where the standard has 1024");
  }
  if (physical_length > source_.size()) {
    throw errorAt(kPhysicalLengthAt, "truncated: the header says " + std::to_string(physical_length) +
                                         " bytes, the file has " + std::to_string(source_.size()));
  }
  if (physical_length % kPageBytes != 0 || physical_length < source_.size()) {
    throw errorAt(kPhysicalLengthAt, "the header's length " + std::to_string(physical_length) +
                                         " is not the file's " + std::to_string(source_.size()) +
                                         " bytes in whole pages");
  }
  const std::uint64_t xml_start = logicalOf(xml_offset_, "the XML section's offset");
  if (xml_offset_ < kHeaderBytes || xml_length_ == 0 || xml_start + xml_length_ > logicalLength()) {
    throw errorAt(kXmlOffsetAt, "the XML section (offset " + std::to_string(xml_offset_) + ", " +
                                    std::to_string(xml_length_) + " bytes) lies outside the file");
  }
}

std::string E57File::readXml() {
  std::string xml(xml_length_, '\0');
  read(logicalOf(xml_offset_, "the XML section's offset"), std::as_writable_bytes(std::span(xml)), "the XML section");
  return xml;
}

std::uint64_t E57File::logicalOf(std::uint64_t physical, const std::string& what) const {
  if (physical % kPageBytes >= kPageDataBytes) {
    throw source_.errorAt(physical, what + " " + std::to_string(physical) + " falls on a page's checksum");
  }
  return physical / kPageBytes * kPageDataBytes + physical % kPageBytes;
}

void E57File::read(std::uint64_t logical, std::span<std::byte> out, const std::string& what) {
  if (logical + out.size() > logicalLength() || logical + out.size() < logical) {
    throw errorAtLogical(std::min(logical, logicalLength()),
                         "truncated: " + what + " runs past the end of the file");
  }
  std::size_t done = 0;
  while (done < out.size()) {
    const std::uint64_t at = logical + done;
    const std::span<const std::byte> data = page(at / kPageDataBytes);
    const std::size_t in_page = at % kPageDataBytes;
    const std::size_t n = std::min<std::size_t>(out.size() - done, kPageDataBytes - in_page);
    std::memcpy(out.data() + done, data.data() + in_page, n);
    done += n;
  }
}

std::span<const std::byte> E57File::page(std::uint64_t index) {
  if (index != cached_page_) {
    std::array<std::byte, kPageBytes> bytes;
    source_.seek(index * kPageBytes);
    source_.readExactly(bytes, "page " + std::to_string(index));
    if (checked_.size() <= index) checked_.resize(source_.size() / kPageBytes + 1, false);
    if (!checked_[index]) {
      const std::uint32_t stored = loadBytes<std::uint32_t>(bytes.data() + kPageDataBytes,
                                                            std::endian::native == std::endian::little);
      const std::uint32_t computed = crc32c(std::span(bytes).first(kPageDataBytes));
      if (stored != computed && kEnforceChecksums) {
        char text[128];
        std::snprintf(text, sizeof text, "page %llu fails its CRC-32C check (stored %08x, computed %08x)",
                      static_cast<unsigned long long>(index), stored, computed);
        throw source_.errorAt(index * kPageBytes, text);
      }
      checked_[index] = true;
    }
    cached_.assign(bytes.begin(), bytes.begin() + kPageDataBytes);
    cached_page_ = index;
  }
  return cached_;
}

}  // namespace plumb::io
