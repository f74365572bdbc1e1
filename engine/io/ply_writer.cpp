#include "engine/io/ply_writer.h"

#include <cassert>
#include <string_view>

#include "engine/core/error.h"

namespace plumb::io {
namespace {

// Digits reserved for the vertex count: enough for any 64-bit count.
constexpr std::size_t kCountDigits = 20;

}  // namespace

std::size_t plyTypeBytes(PlyType type) {
  switch (type) {
    case PlyType::kUInt8:
      return 1;
    case PlyType::kUInt16:
      return 2;
    case PlyType::kUInt32:
    case PlyType::kInt32:
    case PlyType::kFloat32:
      return 4;
    case PlyType::kFloat64:
      return 8;
  }
  return 0;
}

const char* plyTypeName(PlyType type) {
  switch (type) {
    case PlyType::kUInt8:
      return "uchar";
    case PlyType::kUInt16:
      return "ushort";
    case PlyType::kUInt32:
      return "uint";
    case PlyType::kInt32:
      return "int";
    case PlyType::kFloat32:
      return "float";
    case PlyType::kFloat64:
      return "double";
  }
  return "";
}

PlyWriter::PlyWriter(std::string path, std::vector<PlyProperty> properties, const std::vector<std::string>& comments)
    : file_(std::move(path)), properties_(std::move(properties)), comments_(comments) {
  assert(!properties_.empty() && "a PLY vertex needs at least one property");
  for (const auto& comment : comments_) {
    assert(comment.find('\n') == std::string::npos && "PLY comments are single lines");
    (void)comment;
  }
  for (const auto& property : properties_) row_bytes_ += plyTypeBytes(property.type);
  const std::string text = header(0);
  file_.write(text.data(), text.size());
}

std::string PlyWriter::header(std::uint64_t vertex_count) const {
  std::string text = "ply\nformat binary_little_endian 1.0\n";
  for (const auto& comment : comments_) text += "comment " + comment + "\n";
  const std::string count = std::to_string(vertex_count);
  // The padding comment absorbs the digits the count does not use, so the header length
  // never changes between the first write and the final patch.
  text += "comment plumb" + std::string(kCountDigits - count.size(), ' ') + "\n";
  text += "element vertex " + count + "\n";
  for (const auto& property : properties_) {
    text += std::string("property ") + plyTypeName(property.type) + " " + property.name + "\n";
  }
  text += "end_header\n";
  return text;
}

void PlyWriter::writeRows(std::span<const std::byte> rows) {
  assert(rows.size() % row_bytes_ == 0 && "writeRows takes whole rows");
  file_.write(rows);
  row_count_ += rows.size() / row_bytes_;
}

void PlyWriter::finish() {
  const std::string text = header(row_count_);
  file_.overwrite(0, std::as_bytes(std::span(text.data(), text.size())));
  file_.finish();
}

void PlyWriter::commit() {
  file_.commit();
}

}  // namespace plumb::io
