#pragma once
// The physical layer of an E57 file (ASTM E2807-11, "Standard Specification for 3D Imaging Data
// Exchange, Version 1.0", sections 8.1 to 8.4): the 48-byte file header, pages of 1024 bytes
// whose last 4 hold the CRC-32C of the other 1020 (stored big-endian), and the logical byte
// stream that the pages' data bytes form. Every offset in the header and the XML is physical;
// reads are logical. Each page is checked once, when first read; a page that fails its checksum
// stops the reading with the page and its byte offset.

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "engine/io/file_source.h"

namespace plumb::io {

class E57File {
 public:
  static constexpr std::uint64_t kPageBytes = 1024;
  static constexpr std::uint64_t kPageDataBytes = 1020;

  // Opens `path` and checks the header: the "ASTM-E57" signature, major version 1, a page size
  // of 1024, the physical length equal to the file's size (shorter: truncated), and an XML
  // section inside the file. Throws plumb::Error naming the file and the offset.
  explicit E57File(const std::string& path);

  const std::string& path() const { return source_.path(); }
  std::uint32_t versionMajor() const { return version_major_; }
  std::uint32_t versionMinor() const { return version_minor_; }

  // The XML section, its pages checked.
  std::string readXml();

  // The logical offset of physical offset `physical`; throws where it falls on a checksum.
  std::uint64_t logicalOf(std::uint64_t physical, const std::string& what) const;
  // The physical offset of logical offset `logical`.
  static std::uint64_t physicalOf(std::uint64_t logical) {
    return logical / kPageDataBytes * kPageBytes + logical % kPageDataBytes;
  }
  // The logical length of the file (its pages' data bytes).
  std::uint64_t logicalLength() const { return source_.size() / kPageBytes * kPageDataBytes; }

  // Exactly `out.size()` bytes from logical offset `logical`; throws naming `what` and the
  // physical offset where the file ends first or a page fails its checksum.
  void read(std::uint64_t logical, std::span<std::byte> out, const std::string& what);

  // "<path> at byte <physical offset of logical>: <what>".
  Error errorAtLogical(std::uint64_t logical, const std::string& what) const {
    return source_.errorAt(physicalOf(logical), what);
  }
  Error errorAt(std::uint64_t physical, const std::string& what) const { return source_.errorAt(physical, what); }

 private:
  // The data bytes of page `page`, read and checked.
  std::span<const std::byte> page(std::uint64_t page);

  mutable FileSource source_;
  std::uint32_t version_major_ = 0, version_minor_ = 0;
  std::uint64_t xml_offset_ = 0, xml_length_ = 0;
  std::vector<bool> checked_;  // per page: its checksum was verified
  std::uint64_t cached_page_ = UINT64_MAX;
  std::vector<std::byte> cached_;  // the data bytes of cached_page_
};

}  // namespace plumb::io
