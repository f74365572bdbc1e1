#pragma once
// Streaming writer of binary little-endian PLY files with one "vertex" element.
//
// The vertex count is unknown until the last row, so the header reserves room for it and
// finish() patches it in place; a padded comment line keeps the header length fixed, which
// every PLY reader accepts (comments are ignored). The file appears atomically (AtomicFile).

#include <bit>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <span>
#include <string>
#include <vector>

#include "engine/core/atomic_file.h"
#include "engine/io/byte_order.h"  // packLittleEndian, for row packers

namespace plumb::io {

enum class PlyType : std::uint8_t { kUInt8, kUInt16, kUInt32, kInt32, kFloat32, kFloat64 };

struct PlyProperty {
  std::string name;
  PlyType type;
};

std::size_t plyTypeBytes(PlyType type);
const char* plyTypeName(PlyType type);

class PlyWriter {
 public:
  // Creates the temporary output. `comments` become "comment" header lines (no newlines inside).
  PlyWriter(std::string path, std::vector<PlyProperty> properties, const std::vector<std::string>& comments);

  // Bytes per vertex row: the sum of the property sizes, without padding.
  std::size_t rowBytes() const { return row_bytes_; }

  // Appends whole rows, packed little-endian in property order; size must be a multiple of rowBytes().
  void writeRows(std::span<const std::byte> rows);

  std::uint64_t rowCount() const { return row_count_; }
  // Bytes of the file so far, header included.
  std::uint64_t byteCount() const { return file_.size(); }

  // Patches the count, flushes and fsyncs. commit() then moves the file into place.
  void finish();
  void commit();

  const std::string& path() const { return file_.path(); }

 private:
  std::string header(std::uint64_t vertex_count) const;

  AtomicFile file_;
  std::vector<PlyProperty> properties_;
  std::vector<std::string> comments_;
  std::size_t row_bytes_ = 0;
  std::uint64_t row_count_ = 0;
};

}  // namespace plumb::io
