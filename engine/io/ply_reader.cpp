// PLY reader (Greg Turk's polygon file format: ascii, binary_little_endian, binary_big_endian).
//
//   1. Parse the header: the format line, elements with their counts and properties (scalar
//      and list), comments; stop at end_header (a header must end within kMaxHeaderBytes).
//   2. Map the "vertex" element's properties to roles (x y z, colour, intensity, normals) by
//      name, in any order; every other property is ignored and listed in CloudInfo.
//   3. Skip the elements before "vertex"; when the vertex rows have a fixed size, check at open
//      time that the file holds them all, so a truncated file fails before any point is used.
//   4. Stream the vertex rows in batches, decoding each property with the file's byte order.
//   5. After the last vertex, check the data matched the header: a binary file whose last
//      element is "vertex" must end there; an ascii one may only have blank lines left.
//
// Colour: uchar is widened to 16 bits, ushort kept, float and double taken as 0..1. Intensity:
// integers and floats are taken as 16-bit values, rounded and clamped to 0..65535.

#include <algorithm>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstring>
#include <optional>

#include "engine/io/byte_order.h"
#include "engine/io/file_source.h"
#include "engine/io/point_reader.h"
#include "engine/io/text_numbers.h"

namespace plumb::io {
namespace {

constexpr std::uint64_t kMaxHeaderBytes = 1 << 20;

enum class Scalar : std::uint8_t { kInt8, kUInt8, kInt16, kUInt16, kInt32, kUInt32, kFloat32, kFloat64 };

std::optional<Scalar> scalarNamed(std::string_view name) {
  if (name == "char" || name == "int8") return Scalar::kInt8;
  if (name == "uchar" || name == "uint8") return Scalar::kUInt8;
  if (name == "short" || name == "int16") return Scalar::kInt16;
  if (name == "ushort" || name == "uint16") return Scalar::kUInt16;
  if (name == "int" || name == "int32") return Scalar::kInt32;
  if (name == "uint" || name == "uint32") return Scalar::kUInt32;
  if (name == "float" || name == "float32") return Scalar::kFloat32;
  if (name == "double" || name == "float64") return Scalar::kFloat64;
  return std::nullopt;
}

std::size_t scalarBytes(Scalar type) {
  switch (type) {
    case Scalar::kInt8:
    case Scalar::kUInt8:
      return 1;
    case Scalar::kInt16:
    case Scalar::kUInt16:
      return 2;
    case Scalar::kInt32:
    case Scalar::kUInt32:
    case Scalar::kFloat32:
      return 4;
    case Scalar::kFloat64:
      return 8;
  }
  return 0;
}

bool isFloat(Scalar type) {
  return type == Scalar::kFloat32 || type == Scalar::kFloat64;
}

// Inlined into the row loops: a call per property was a fifth of reading a binary file.
[[gnu::always_inline]] inline double decode(const std::byte* p, Scalar type, bool swap) {
  switch (type) {
    case Scalar::kInt8:
      return loadBytes<std::int8_t>(p, false);
    case Scalar::kUInt8:
      return loadBytes<std::uint8_t>(p, false);
    case Scalar::kInt16:
      return loadBytes<std::int16_t>(p, swap);
    case Scalar::kUInt16:
      return loadBytes<std::uint16_t>(p, swap);
    case Scalar::kInt32:
      return loadBytes<std::int32_t>(p, swap);
    case Scalar::kUInt32:
      return loadBytes<std::uint32_t>(p, swap);
    case Scalar::kFloat32:
      return loadBytes<float>(p, swap);
    case Scalar::kFloat64:
      return loadBytes<double>(p, swap);
  }
  return 0.0;
}

struct Property {
  std::string name;
  Scalar type;
  bool is_list = false;
  Scalar count_type = Scalar::kUInt8;  // lists only
  std::size_t offset = 0;              // within a fixed-size row
};

struct Element {
  std::string name;
  std::uint64_t count = 0;
  std::vector<Property> properties;
  bool fixed_size = true;
  std::size_t row_bytes = 0;
};

enum Role : int { kX, kY, kZ, kRed, kGreen, kBlue, kIntensity, kNx, kNy, kNz, kRoleCount };

int roleNamed(std::string_view name) {
  static constexpr std::pair<std::string_view, int> kNames[] = {{"x", kX},
                                                                {"y", kY},
                                                                {"z", kZ},
                                                                {"red", kRed},
                                                                {"green", kGreen},
                                                                {"blue", kBlue},
                                                                {"r", kRed},
                                                                {"g", kGreen},
                                                                {"b", kBlue},
                                                                {"diffuse_red", kRed},
                                                                {"diffuse_green", kGreen},
                                                                {"diffuse_blue", kBlue},
                                                                {"intensity", kIntensity},
                                                                {"scalar_intensity", kIntensity},
                                                                {"scalar_Intensity", kIntensity},
                                                                {"nx", kNx},
                                                                {"ny", kNy},
                                                                {"nz", kNz},
                                                                {"normal_x", kNx},
                                                                {"normal_y", kNy},
                                                                {"normal_z", kNz}};
  for (const auto& [known, role] : kNames) {
    if (known == name) return role;
  }
  return -1;
}

[[gnu::always_inline]] inline std::uint16_t toColour(double value, Scalar type) {
  if (!std::isfinite(value)) return 0;
  // An ascii file may write any number for a uchar property: clamp before narrowing.
  if (type == Scalar::kUInt8)
    return widenColour(static_cast<std::uint8_t>(std::clamp(roundedToWhole(value), 0.0, 255.0)));
  const double scaled = isFloat(type) ? value * 65535.0 : value;
  return static_cast<std::uint16_t>(std::clamp(roundedToWhole(scaled), 0.0, 65535.0));
}

std::vector<std::string_view> splitWords(std::string_view line) {
  std::vector<std::string_view> words;
  splitFields(line, /*comma=*/false, words);
  return words;
}

class PlyReader final : public PointReader {
 public:
  explicit PlyReader(const std::string& path) : PointReader(path), source_(path) {
    parseHeader();
    skipElementsBeforeVertex();
    checkVertexDataFits();
  }

  bool read(PointBatch& batch, std::size_t max_points) override {
    batch.clear();
    while (batch.size() < max_points && remaining_ > 0) {
      const std::uint64_t take = std::min<std::uint64_t>(max_points - batch.size(), remaining_);
      if (ascii_) {
        readAsciiRows(batch, take);
      } else {
        switch (common_layout_) {
          case Layout::kDouble:
            readCommonRows<double>(batch, take);
            break;
          case Layout::kFloat:
            readCommonRows<float>(batch, take);
            break;
          case Layout::kOther:
            readBinaryRows(batch, take);
            break;
        }
      }
    }
    if (remaining_ == 0 && !checked_end_) checkEnd();
    return !batch.points.empty() || remaining_ > 0;
  }

 private:
  void parseHeader() {
    std::string line;
    if (!source_.readLine(line, 64) || line != "ply")
      throw source_.errorAt(0, "not a PLY file: it must start with 'ply'");
    Element* current = nullptr;
    for (;;) {
      if (source_.offset() > kMaxHeaderBytes) throw source_.errorHere("no end_header in the first megabyte");
      if (!source_.readLine(line, kMaxHeaderBytes)) throw source_.errorHere("truncated header: no end_header");
      const auto words = splitWords(line);
      if (words.empty()) continue;
      const std::string_view keyword = words[0];
      if (keyword == "end_header") break;
      if (keyword == "comment" || keyword == "obj_info") continue;
      if (keyword == "format") {
        if (words.size() != 3 || words[2] != "1.0") throw source_.errorAtLine("expected 'format <encoding> 1.0'");
        if (words[1] == "ascii") {
          ascii_ = true;
        } else if (words[1] == "binary_little_endian") {
          swap_ = std::endian::native != std::endian::little;
        } else if (words[1] == "binary_big_endian") {
          swap_ = std::endian::native != std::endian::big;
        } else {
          throw source_.errorAtLine("unknown PLY encoding '" + std::string(words[1]) + "'");
        }
        info_.format = "PLY " + std::string(words[1]);
      } else if (keyword == "element") {
        std::uint64_t count = 0;
        if (words.size() != 3 ||
            std::from_chars(words[2].data(), words[2].data() + words[2].size(), count).ec != std::errc()) {
          throw source_.errorAtLine("expected 'element <name> <count>'");
        }
        elements_.push_back({std::string(words[1]), count, {}, true, 0});
        current = &elements_.back();
      } else if (keyword == "property") {
        if (current == nullptr) throw source_.errorAtLine("property before any element");
        Property property;
        if (words.size() == 5 && words[1] == "list") {
          const auto count_type = scalarNamed(words[2]);
          const auto item_type = scalarNamed(words[3]);
          if (!count_type || !item_type || isFloat(*count_type)) {
            throw source_.errorAtLine("bad list property types '" + line + "'");
          }
          property = {std::string(words[4]), *item_type, true, *count_type, 0};
          current->fixed_size = false;
        } else if (words.size() == 3) {
          const auto type = scalarNamed(words[1]);
          if (!type) throw source_.errorAtLine("unknown property type '" + std::string(words[1]) + "'");
          property = {std::string(words[2]), *type, false, Scalar::kUInt8, current->row_bytes};
          current->row_bytes += scalarBytes(*type);
        } else {
          throw source_.errorAtLine("expected 'property <type> <name>' or 'property list <type> <type> <name>'");
        }
        current->properties.push_back(std::move(property));
      } else {
        throw source_.errorAtLine("unknown header line '" + line + "'");
      }
    }
    if (info_.format.empty()) throw source_.errorHere("the header has no format line");

    const auto vertex =
        std::find_if(elements_.begin(), elements_.end(), [](const Element& e) { return e.name == "vertex"; });
    if (vertex == elements_.end()) throw source_.errorAt(0, "no 'vertex' element: this PLY holds no points");
    vertex_index_ = static_cast<std::size_t>(vertex - elements_.begin());
    roles_.fill(-1);
    for (std::size_t i = 0; i < vertex->properties.size(); ++i) {
      const Property& property = vertex->properties[i];
      const int role = property.is_list ? -1 : roleNamed(property.name);
      if (role < 0 || roles_[static_cast<std::size_t>(role)] >= 0) {
        info_.ignored_fields.push_back(property.name + (property.is_list ? " (list)" : ""));
      } else {
        roles_[static_cast<std::size_t>(role)] = static_cast<int>(i);
      }
    }
    if (roles_[kX] < 0 || roles_[kY] < 0 || roles_[kZ] < 0) {
      throw source_.errorAt(0, "the vertex element lacks x, y or z");
    }
    info_.attributes.colour = roles_[kRed] >= 0 && roles_[kGreen] >= 0 && roles_[kBlue] >= 0;
    info_.attributes.intensity = roles_[kIntensity] >= 0;
    info_.attributes.normals = roles_[kNx] >= 0 && roles_[kNy] >= 0 && roles_[kNz] >= 0;
    info_.declared_points = vertex->count;
    remaining_ = vertex->count;
    for (std::size_t r = 0; r < kRoleCount; ++r) {
      if (roles_[r] < 0) continue;
      const Property& property = vertex->properties[static_cast<std::size_t>(roles_[r])];
      decoders_.push_back({r, property.offset, property.type});
    }
    common_layout_ = commonLayout();
  }

  // Which of the layouts most writers use the file has: little-endian on a little-endian host,
  // x y z all float or all double, colour (if any) 8-bit, intensity (if any) 16-bit, no normals.
  enum class Layout { kOther, kFloat, kDouble };
  Layout commonLayout() const {
    if (ascii_ || swap_ || !elements_[vertex_index_].fixed_size || info_.attributes.normals) return Layout::kOther;
    const auto types = roleTypes();
    const auto only = [&](std::initializer_list<int> roles, Scalar type) {
      return std::all_of(roles.begin(), roles.end(), [&](int r) { return types[static_cast<std::size_t>(r)] == type; });
    };
    if (info_.attributes.colour && !only({kRed, kGreen, kBlue}, Scalar::kUInt8)) return Layout::kOther;
    if (info_.attributes.intensity && !only({kIntensity}, Scalar::kUInt16)) return Layout::kOther;
    if (only({kX, kY, kZ}, Scalar::kFloat64)) return Layout::kDouble;
    if (only({kX, kY, kZ}, Scalar::kFloat32)) return Layout::kFloat;
    return Layout::kOther;
  }

  // The next `count` fixed-size rows into rows_, in one read.
  void readRowBlock(std::uint64_t count) {
    rows_.resize(static_cast<std::size_t>(count) * elements_[vertex_index_].row_bytes);
    source_.readExactly(rows_, "the vertex data");
  }

  // The rows of a common layout: each field loaded as what it is, with no conversion through a
  // double per property (what emit() makes of them is the same: whole 8-bit colours widened,
  // 16-bit intensities as they are). A third of the time of a pass over a PLY.
  template <typename Coordinate>
  void readCommonRows(PointBatch& batch, std::uint64_t count) {
    const Element& vertex = elements_[vertex_index_];
    const auto offset = [&](Role role) { return vertex.properties[static_cast<std::size_t>(roles_[role])].offset; };
    const std::size_t x = offset(kX), y = offset(kY), z = offset(kZ);
    const bool colour = info_.attributes.colour, intensity = info_.attributes.intensity;
    const std::size_t red = colour ? offset(kRed) : 0, green = colour ? offset(kGreen) : 0;
    const std::size_t blue = colour ? offset(kBlue) : 0, level = intensity ? offset(kIntensity) : 0;
    readRowBlock(count);
    for (std::uint64_t row = 0; row < count; ++row) {
      const std::byte* base = rows_.data() + row * vertex.row_bytes;
      PointRecord point{loadLittleEndian<Coordinate>(base + x),
                        loadLittleEndian<Coordinate>(base + y),
                        loadLittleEndian<Coordinate>(base + z),
                        {0, 0, 0},
                        0};
      if (colour) {
        point.rgb = {widenColour(static_cast<std::uint8_t>(base[red])),
                     widenColour(static_cast<std::uint8_t>(base[green])),
                     widenColour(static_cast<std::uint8_t>(base[blue]))};
      }
      if (intensity) point.intensity = loadLittleEndian<std::uint16_t>(base + level);
      deliver(batch, point);
    }
    remaining_ -= count;
  }

  void skipElementsBeforeVertex() {
    for (std::size_t e = 0; e < vertex_index_; ++e) {
      const Element& element = elements_[e];
      for (std::uint64_t row = 0; row < element.count; ++row) {
        if (ascii_) {
          if (!source_.readLine(line_))
            throw source_.errorHere("truncated: the file ends inside element '" + element.name + "'");
        } else if (element.fixed_size) {
          if (element.row_bytes > 0 && element.count > source_.remaining() / element.row_bytes) {
            throw source_.errorHere("truncated: element '" + element.name + "' declares " +
                                    std::to_string(element.count) + " rows, more than the file holds");
          }
          source_.skip(element.count * element.row_bytes, "element '" + element.name + "'");
          break;
        } else {
          skipBinaryRow(element);
        }
      }
    }
  }

  void skipBinaryRow(const Element& element) {
    for (const Property& property : element.properties) {
      if (!property.is_list) {
        source_.skip(scalarBytes(property.type), "element '" + element.name + "'");
        continue;
      }
      std::array<std::byte, 8> count_bytes{};
      source_.readExactly(std::span(count_bytes).first(scalarBytes(property.count_type)), "a list length");
      const double count = decode(count_bytes.data(), property.count_type, swap_);
      if (count < 0) throw source_.errorHere("negative list length");
      source_.skip(static_cast<std::uint64_t>(count) * scalarBytes(property.type), "a list");
    }
  }

  // A fixed-size binary vertex block must fit in the file, or the file is truncated.
  void checkVertexDataFits() {
    const Element& vertex = elements_[vertex_index_];
    if (ascii_ || !vertex.fixed_size) return;
    const std::uint64_t needed = vertex.count * vertex.row_bytes;
    if (vertex.row_bytes > 0 && vertex.count > source_.remaining() / vertex.row_bytes) {
      throw source_.errorHere("truncated: the header declares " + std::to_string(vertex.count) + " vertices of " +
                              std::to_string(vertex.row_bytes) + " bytes (" + std::to_string(needed) +
                              " bytes) but only " + std::to_string(source_.remaining()) + " bytes follow, enough for " +
                              std::to_string(source_.remaining() / vertex.row_bytes));
    }
  }

  [[gnu::always_inline]] void emit(PointBatch& batch, const std::array<double, kRoleCount>& value,
                                   const std::array<Scalar, kRoleCount>& type) {
    PointRecord point{value[kX], value[kY], value[kZ], {0, 0, 0}, 0};
    if (info_.attributes.colour) {
      point.rgb = {toColour(value[kRed], type[kRed]), toColour(value[kGreen], type[kGreen]),
                   toColour(value[kBlue], type[kBlue])};
    }
    if (info_.attributes.intensity) point.intensity = intensityFrom(value[kIntensity]);
    deliver(batch, point,
            {static_cast<float>(value[kNx]), static_cast<float>(value[kNy]), static_cast<float>(value[kNz])});
  }

  std::array<Scalar, kRoleCount> roleTypes() const {
    std::array<Scalar, kRoleCount> types{};
    const Element& vertex = elements_[vertex_index_];
    for (std::size_t r = 0; r < kRoleCount; ++r) {
      if (roles_[r] >= 0) types[r] = vertex.properties[static_cast<std::size_t>(roles_[r])].type;
    }
    return types;
  }

  void readBinaryRows(PointBatch& batch, std::uint64_t count) {
    const Element& vertex = elements_[vertex_index_];
    const auto types = roleTypes();
    std::array<double, kRoleCount> value{};
    if (!vertex.fixed_size) {
      // Rare: list properties inside the vertex element; decode row by row.
      for (std::uint64_t row = 0; row < count; ++row, --remaining_) {
        for (std::size_t p = 0; p < vertex.properties.size(); ++p) {
          const Property& property = vertex.properties[p];
          if (property.is_list) {
            skipBinaryRow(Element{vertex.name, 1, {property}, false, 0});
            continue;
          }
          std::array<std::byte, 8> bytes{};
          source_.readExactly(std::span(bytes).first(scalarBytes(property.type)), "a vertex");
          for (std::size_t r = 0; r < kRoleCount; ++r) {
            if (roles_[r] == static_cast<int>(p)) value[r] = decode(bytes.data(), property.type, swap_);
          }
        }
        emit(batch, value, types);
      }
      return;
    }
    readRowBlock(count);
    for (std::uint64_t row = 0; row < count; ++row) {
      const std::byte* base = rows_.data() + row * vertex.row_bytes;
      for (const Decoder& d : decoders_) value[d.role] = decode(base + d.offset, d.type, swap_);
      emit(batch, value, types);
    }
    remaining_ -= count;
  }

  void readAsciiRows(PointBatch& batch, std::uint64_t count) {
    const Element& vertex = elements_[vertex_index_];
    const auto types = roleTypes();
    std::array<double, kRoleCount> value{};
    for (std::uint64_t row = 0; row < count; ++row, --remaining_) {
      if (!source_.readLine(line_)) {
        throw source_.errorHere("truncated: the header declares " + std::to_string(vertex.count) +
                                " vertices, the file ends after " + std::to_string(vertex.count - remaining_));
      }
      const auto words = splitWords(line_);
      std::size_t w = 0;
      for (std::size_t p = 0; p < vertex.properties.size(); ++p) {
        const Property& property = vertex.properties[p];
        double number = 0.0;
        if (w >= words.size() || !parseNumber(words[w], number)) {
          throw source_.errorAtLine("expected a number for property '" + property.name + "' (vertex " +
                                    std::to_string(vertex.count - remaining_) + ")");
        }
        ++w;
        if (property.is_list) {
          if (!(number >= 0.0 && number <= static_cast<double>(words.size() - w))) {
            throw source_.errorAtLine("list '" + property.name + "' is longer than the line");
          }
          w += static_cast<std::size_t>(number);
          continue;
        }
        for (std::size_t r = 0; r < kRoleCount; ++r) {
          if (roles_[r] == static_cast<int>(p)) value[r] = number;
        }
      }
      if (w != words.size()) throw source_.errorAtLine("more values than the vertex element has properties");
      emit(batch, value, types);
    }
  }

  void checkEnd() {
    checked_end_ = true;
    if (vertex_index_ + 1 != elements_.size()) return;  // other elements follow; they are not points
    if (ascii_) {
      while (source_.readLine(line_)) {
        if (!splitWords(line_).empty()) {
          throw source_.errorAtLine("data after the last of the " + std::to_string(*info_.declared_points) +
                                    " declared vertices: the header's count disagrees with the data");
        }
      }
    } else if (!source_.atEnd()) {
      throw source_.errorHere(std::to_string(source_.remaining()) + " bytes after the last of the " +
                              std::to_string(*info_.declared_points) +
                              " declared vertices: the header's count disagrees with the data");
    }
  }

  FileSource source_;
  bool ascii_ = false;
  bool swap_ = false;
  std::vector<Element> elements_;
  std::size_t vertex_index_ = 0;
  std::array<int, kRoleCount> roles_{};
  // The kept properties of a fixed-size row: which role, where, what type.
  struct Decoder {
    std::size_t role;
    std::size_t offset;
    Scalar type;
  };
  std::vector<Decoder> decoders_;
  Layout common_layout_ = Layout::kOther;
  std::uint64_t remaining_ = 0;
  bool checked_end_ = false;
  std::vector<std::byte> rows_;
  std::string line_;
};

}  // namespace

std::unique_ptr<PointReader> openPly(const std::string& path) {
  return std::make_unique<PlyReader>(path);
}

}  // namespace plumb::io
