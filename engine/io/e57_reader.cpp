// E57 reader (ASTM E2807-11, "Standard Specification for 3D Imaging Data Exchange, Version
// 1.0"). The physical layer (header, pages, checksums) is e57_file.h; this file reads the XML
// section (section 8.4 and the element types of section 7) with pugixml and decodes the point
// records of every data3D scan (section 9, compressed vectors with the bitPackCodec).
//
//   1. The XML: /e57Root/data3D holds one Structure per scan: its name, an optional pose
//      (a unit quaternion w x y z and a translation, scan to world), the optional intensity and
//      colour limits, and `points`, a CompressedVector with the physical offset of its binary
//      section, its record count and a prototype: the fields of one record, in the order of
//      their bytestreams (nested Structures and Vectors depth-first). Every element of the
//      standard's types is checked as it is read (its type attribute, its numbers).
//   2. Each scan's binary section: a 32-byte header (section id 1, logical length, the physical
//      offset of the first data packet), then packets (section 9.4): data packets (type 1) carry
//      one buffer per bytestream; index (0) and empty (2) packets are skipped.
//   3. The bytestreams (section 9.5, bitPackCodec): a field's values follow one another in its
//      own stream, across packets, least significant bit first in little-endian bytes. An Integer
//      of [min, max] takes ceil(log2(max - min + 1)) bits and is min + the raw value (0 bits when
//      min = max: nothing stored); a ScaledInteger is (min + raw) * scale + offset; a Float is a
//      32- or 64-bit IEEE value; a String a length prefix (1 byte when its lowest bit is 0, else
//      8) and its bytes. Records are decoded as far as every stream holds them.
//   4. A record becomes a point: cartesianX/Y/Z, or sphericalRange/Azimuth/Elevation turned
//      Cartesian; moved into the world by the scan's pose. A cartesianInvalidState (or
//      sphericalInvalidState) other than 0 marks the point invalid: it is skipped and counted
//      (ReadCounts::non_finite, the points without a valid position).
//      Intensity is normalised by intensityLimits (else the field's own bounds) to 0..65535 and
//      colour by colorLimits likewise; isIntensityInvalid and isColorInvalid make them 0 for the
//      point. The normals extension (normalX/Y/Z, any prefix) is read and turned by the pose.
//      Every other field is listed as ignored, and so are images2D.
//   5. The scans one after another, as one cloud. The record counts are checked: a section that
//      ends before its records do is truncated.

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <optional>
#include <pugixml.hpp>
#include <string_view>

#include "engine/io/byte_order.h"
#include "engine/io/e57_file.h"
#include "engine/io/point_reader.h"

namespace plumb::io {
namespace {

// ---- The XML -------------------------------------------------------------------------------

// Reads elements of the XML section, naming the element's path in every error.
class XmlReader {
 public:
  XmlReader(const E57File& file) : file_(file) {}

  Error error(const std::string& path, const std::string& what) const {
    return fileError(file_.path(), "XML section, " + path + ": " + what);
  }

  // The element's type attribute, which must be one of `types` (separated by '|').
  std::string typeOf(const pugi::xml_node& node, const std::string& path, std::string_view types) const {
    const std::string type = node.attribute("type").as_string();
    std::string_view rest = types;
    while (!rest.empty()) {
      const std::size_t bar = rest.find('|');
      if (rest.substr(0, bar) == type) return type;
      rest = bar == std::string_view::npos ? std::string_view{} : rest.substr(bar + 1);
    }
    throw error(path, type.empty() ? "no type attribute" : "type '" + type + "', expected " + std::string(types));
  }

  // A number: the element's text (Integer, ScaledInteger, Float; empty is 0).
  double number(const pugi::xml_node& node, const std::string& path) const {
    const std::string type = typeOf(node, path, "Integer|ScaledInteger|Float");
    if (type == "ScaledInteger") {
      return static_cast<double>(integerText(node.child_value(), path)) * attributeNumber(node, "scale", path, 1.0) +
             attributeNumber(node, "offset", path, 0.0);
    }
    if (type == "Integer") return static_cast<double>(integerText(node.child_value(), path));
    return floatText(node.child_value(), path);
  }

  // The number of an optional child, or nothing.
  std::optional<double> childNumber(const pugi::xml_node& node, const char* name, const std::string& path) const {
    const pugi::xml_node child = node.child(name);
    if (!child) return std::nullopt;
    return number(child, path + "/" + name);
  }

  double attributeNumber(const pugi::xml_node& node, const char* name, const std::string& path, double fallback) const {
    const pugi::xml_attribute attribute = node.attribute(name);
    if (!attribute) return fallback;
    return floatText(attribute.value(), path + "@" + name);
  }

  std::int64_t attributeInteger(const pugi::xml_node& node, const char* name, const std::string& path,
                                std::int64_t fallback) const {
    const pugi::xml_attribute attribute = node.attribute(name);
    if (!attribute) return fallback;
    return integerText(attribute.value(), path + "@" + name);
  }

  std::int64_t integerText(std::string_view text, const std::string& path) const {
    text = trimmed(text);
    if (text.empty()) return 0;
    std::int64_t value = 0;
    const auto [end, code] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (code != std::errc() || end != text.data() + text.size()) {
      throw error(path, "'" + std::string(text) + "' is not a 64-bit integer");
    }
    return value;
  }

  double floatText(std::string_view text, const std::string& path) const {
    text = trimmed(text);
    if (text.empty()) return 0.0;
    double value = 0.0;
    const auto [end, code] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (code != std::errc() || end != text.data() + text.size() || !std::isfinite(value)) {
      throw error(path, "'" + std::string(text) + "' is not a finite number");
    }
    return value;
  }

 private:
  static std::string_view trimmed(std::string_view text) {
    const auto first = text.find_first_not_of(" \t\r\n");
    if (first == std::string_view::npos) return {};
    return text.substr(first, text.find_last_not_of(" \t\r\n") - first + 1);
  }

  const E57File& file_;
};

enum class Encoding { kInteger, kScaledInteger, kFloat, kString };

// One terminal field of a record's prototype, with its bytestream's coding.
struct Field {
  std::string name;  // the path below the prototype, e.g. "cartesianX", "nor:normalX"
  Encoding encoding = Encoding::kFloat;
  std::int64_t minimum = 0, maximum = 0;  // Integer and ScaledInteger
  double scale = 1.0, offset = 0.0;       // ScaledInteger
  bool single_precision = false;          // Float
  double float_minimum = 0.0, float_maximum = 0.0;
  unsigned bits = 0;  // per value: the integers' packed width, a Float's 32 or 64; 0 for strings

  // The field's declared value range (for intensity and colour without limits), if finite.
  std::optional<std::pair<double, double>> bounds() const {
    switch (encoding) {
      case Encoding::kInteger:
        return std::pair{static_cast<double>(minimum), static_cast<double>(maximum)};
      case Encoding::kScaledInteger:
        return std::pair{static_cast<double>(minimum) * scale + offset, static_cast<double>(maximum) * scale + offset};
      case Encoding::kFloat:
        if (std::abs(float_minimum) < 1e30 && std::abs(float_maximum) < 1e30)
          return std::pair{float_minimum, float_maximum};
        return std::nullopt;
      case Encoding::kString:
        return std::nullopt;
    }
    return std::nullopt;
  }
};

// What a field means to Plumb.
enum class Role {
  kX,
  kY,
  kZ,
  kRange,
  kAzimuth,
  kElevation,
  kCartesianInvalid,
  kSphericalInvalid,
  kIntensity,
  kIntensityInvalid,
  kRed,
  kGreen,
  kBlue,
  kColourInvalid,
  kNormalX,
  kNormalY,
  kNormalZ,
  kIgnored
};
constexpr std::size_t kRoles = static_cast<std::size_t>(Role::kIgnored);

Role roleOf(const std::string& name) {
  static const std::map<std::string_view, Role> roles{{"cartesianX", Role::kX},
                                                      {"cartesianY", Role::kY},
                                                      {"cartesianZ", Role::kZ},
                                                      {"sphericalRange", Role::kRange},
                                                      {"sphericalAzimuth", Role::kAzimuth},
                                                      {"sphericalElevation", Role::kElevation},
                                                      {"cartesianInvalidState", Role::kCartesianInvalid},
                                                      {"sphericalInvalidState", Role::kSphericalInvalid},
                                                      {"intensity", Role::kIntensity},
                                                      {"isIntensityInvalid", Role::kIntensityInvalid},
                                                      {"colorRed", Role::kRed},
                                                      {"colorGreen", Role::kGreen},
                                                      {"colorBlue", Role::kBlue},
                                                      {"isColorInvalid", Role::kColourInvalid}};
  if (const auto it = roles.find(name); it != roles.end()) return it->second;
  // The surface normals extension (libE57Format's E57_EXT_surface_normals), whatever its prefix.
  const std::size_t colon = name.find(':');
  if (colon != std::string::npos && name.find('/') == std::string::npos) {
    const std::string_view local = std::string_view(name).substr(colon + 1);
    if (local == "normalX") return Role::kNormalX;
    if (local == "normalY") return Role::kNormalY;
    if (local == "normalZ") return Role::kNormalZ;
  }
  return Role::kIgnored;
}

unsigned bitsFor(std::int64_t minimum, std::int64_t maximum) {
  const std::uint64_t range = static_cast<std::uint64_t>(maximum) - static_cast<std::uint64_t>(minimum);
  return static_cast<unsigned>(std::bit_width(range));
}

// The limits a scan states for a quantity (intensityLimits, colorLimits), where they span a range.
using Limits = std::optional<std::pair<double, double>>;

struct Scan {
  std::string name;   // its name, else "data3D[i]"
  std::string label;  // "data3D[i] 'name'" for messages
  Eigen::Quaterniond rotation = Eigen::Quaterniond::Identity();
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();
  std::uint64_t section_offset = 0;  // physical
  std::uint64_t records = 0;
  std::vector<Field> fields;
  std::array<int, kRoles> field_of{};  // per role: its field's index, or -1
  Limits intensity_limits;
  std::array<Limits, 3> colour_limits;

  int field(Role role) const { return field_of[static_cast<std::size_t>(role)]; }
  bool has(Role role) const { return field(role) >= 0; }
};

void flattenPrototype(const XmlReader& xml, const pugi::xml_node& node, const std::string& name,
                      const std::string& path, std::vector<Field>& fields) {
  const std::string type = xml.typeOf(node, path, "Integer|ScaledInteger|Float|String|Structure|Vector");
  if (type == "Structure" || type == "Vector") {
    for (const pugi::xml_node& child : node.children()) {
      if (child.type() != pugi::node_element) continue;
      const std::string child_name = name.empty() ? child.name() : name + "/" + child.name();
      flattenPrototype(xml, child, child_name, path + "/" + child.name(), fields);
    }
    return;
  }
  Field field;
  field.name = name;
  if (type == "Integer" || type == "ScaledInteger") {
    field.encoding = type == "Integer" ? Encoding::kInteger : Encoding::kScaledInteger;
    field.minimum = xml.attributeInteger(node, "minimum", path, std::numeric_limits<std::int64_t>::min());
    field.maximum = xml.attributeInteger(node, "maximum", path, std::numeric_limits<std::int64_t>::max());
    if (field.minimum > field.maximum) {
      throw xml.error(path,
                      "minimum " + std::to_string(field.minimum) + " above maximum " + std::to_string(field.maximum));
    }
    field.bits = bitsFor(field.minimum, field.maximum);
    if (type == "ScaledInteger") {
      field.scale = xml.attributeNumber(node, "scale", path, 1.0);
      field.offset = xml.attributeNumber(node, "offset", path, 0.0);
      if (field.scale == 0.0) throw xml.error(path, "scale 0");
    }
  } else if (type == "Float") {
    field.encoding = Encoding::kFloat;
    const std::string precision = node.attribute("precision") ? node.attribute("precision").as_string() : "double";
    if (precision != "single" && precision != "double") {
      throw xml.error(path, "precision '" + precision + "', expected single or double");
    }
    field.single_precision = precision == "single";
    const double largest =
        field.single_precision ? std::numeric_limits<float>::max() : std::numeric_limits<double>::max();
    field.float_minimum = xml.attributeNumber(node, "minimum", path, -largest);
    field.float_maximum = xml.attributeNumber(node, "maximum", path, largest);
    field.bits = field.single_precision ? 32 : 64;
  } else {
    field.encoding = Encoding::kString;
  }
  fields.push_back(std::move(field));
}

Limits limitsOf(const XmlReader& xml, const pugi::xml_node& node, const char* minimum, const char* maximum,
                const std::string& path) {
  if (!node) return std::nullopt;
  const std::optional<double> low = xml.childNumber(node, minimum, path);
  const std::optional<double> high = xml.childNumber(node, maximum, path);
  if (!low || !high || !(*high > *low)) return std::nullopt;  // absent or degenerate: the field's own bounds
  return std::pair{*low, *high};
}

Scan readScan(const XmlReader& xml, const pugi::xml_node& node, std::size_t index) {
  const std::string path = "/data3D/" + std::to_string(index);
  xml.typeOf(node, path, "Structure");
  Scan scan;
  const std::string name = node.child("name").child_value();
  scan.label = "data3D[" + std::to_string(index) + "]" + (name.empty() ? "" : " '" + name + "'");
  scan.name = name.empty() ? "data3D[" + std::to_string(index) + "]" : name;
  if (const pugi::xml_node pose = node.child("pose")) {
    xml.typeOf(pose, path + "/pose", "Structure");
    if (const pugi::xml_node rotation = pose.child("rotation")) {
      const std::string at = path + "/pose/rotation";
      xml.typeOf(rotation, at, "Structure");
      const double w = xml.childNumber(rotation, "w", at).value_or(1.0);
      const double x = xml.childNumber(rotation, "x", at).value_or(0.0);
      const double y = xml.childNumber(rotation, "y", at).value_or(0.0);
      const double z = xml.childNumber(rotation, "z", at).value_or(0.0);
      const double norm = std::sqrt(w * w + x * x + y * y + z * z);
      // The standard asks for a unit quaternion; writers round. Far from unit is an error.
      if (std::abs(norm - 1.0) > 1e-3) {
        throw xml.error(at, "the rotation (" + std::to_string(w) + ", " + std::to_string(x) + ", " + std::to_string(y) +
                                ", " + std::to_string(z) + ") is not a unit quaternion");
      }
      scan.rotation = Eigen::Quaterniond(w / norm, x / norm, y / norm, z / norm);
    }
    if (const pugi::xml_node translation = pose.child("translation")) {
      const std::string at = path + "/pose/translation";
      xml.typeOf(translation, at, "Structure");
      scan.translation = {xml.childNumber(translation, "x", at).value_or(0.0),
                          xml.childNumber(translation, "y", at).value_or(0.0),
                          xml.childNumber(translation, "z", at).value_or(0.0)};
    }
  }
  scan.intensity_limits =
      limitsOf(xml, node.child("intensityLimits"), "intensityMinimum", "intensityMaximum", path + "/intensityLimits");
  const pugi::xml_node colour = node.child("colorLimits");
  scan.colour_limits = {limitsOf(xml, colour, "colorRedMinimum", "colorRedMaximum", path + "/colorLimits"),
                        limitsOf(xml, colour, "colorGreenMinimum", "colorGreenMaximum", path + "/colorLimits"),
                        limitsOf(xml, colour, "colorBlueMinimum", "colorBlueMaximum", path + "/colorLimits")};

  const pugi::xml_node points = node.child("points");
  const std::string points_path = path + "/points";
  if (!points) throw xml.error(path, "no points");
  xml.typeOf(points, points_path, "CompressedVector");
  const std::int64_t offset = xml.attributeInteger(points, "fileOffset", points_path, -1);
  const std::int64_t records = xml.attributeInteger(points, "recordCount", points_path, -1);
  if (offset < 0) throw xml.error(points_path, "no fileOffset");
  if (records < 0) throw xml.error(points_path, "no recordCount");
  scan.section_offset = static_cast<std::uint64_t>(offset);
  scan.records = static_cast<std::uint64_t>(records);
  const pugi::xml_node prototype = points.child("prototype");
  if (!prototype) throw xml.error(points_path, "no prototype");
  xml.typeOf(prototype, points_path + "/prototype", "Structure");
  flattenPrototype(xml, prototype, "", points_path + "/prototype", scan.fields);
  if (scan.fields.empty()) throw xml.error(points_path + "/prototype", "no fields");
  // The bitPackCodec is the standard's only codec, and the default for a field no codec names.
  if (const pugi::xml_node codecs = points.child("codecs")) {
    for (const pugi::xml_node& codec : codecs.children()) {
      if (codec.type() != pugi::node_element) continue;
      if (!codec.child("bitPackCodec")) {
        throw xml.error(points_path + "/codecs", "a codec other than bitPackCodec: its fields' encoding is unknown");
      }
    }
  }

  scan.field_of.fill(-1);
  for (std::size_t f = 0; f < scan.fields.size(); ++f) {
    const Role role = roleOf(scan.fields[f].name);
    if (role == Role::kIgnored) continue;
    if (scan.fields[f].encoding == Encoding::kString) {
      throw xml.error(points_path + "/prototype/" + scan.fields[f].name, "a String where the standard has a number");
    }
    scan.field_of[static_cast<std::size_t>(role)] = static_cast<int>(f);
  }
  const bool cartesian = scan.has(Role::kX) && scan.has(Role::kY) && scan.has(Role::kZ);
  const bool spherical = scan.has(Role::kRange) && scan.has(Role::kAzimuth) && scan.has(Role::kElevation);
  if (!cartesian && !spherical) {
    throw xml.error(points_path + "/prototype", "neither cartesianX/Y/Z nor sphericalRange/Azimuth/Elevation");
  }
  return scan;
}

// ---- The bytestreams -----------------------------------------------------------------------

// One field's bytestream: the bytes its packets have brought so far, and the next bit to read.
class Bytestream {
 public:
  void append(std::span<const std::byte> bytes) {
    // Drop the bytes already read before growing.
    const std::size_t consumed = bit_ / 8;
    if (consumed > 0) {
      bytes_.erase(bytes_.begin(), bytes_.begin() + static_cast<std::ptrdiff_t>(consumed));
      bit_ %= 8;
    }
    bytes_.insert(bytes_.end(), bytes.begin(), bytes.end());
  }

  // How many more values of `field` the stream holds whole; `limit` when a value takes no bits.
  std::uint64_t available(const Field& field, std::uint64_t limit) const {
    if (field.encoding == Encoding::kString) return stringsAvailable(limit);
    if (field.bits == 0) return limit;
    return std::min<std::uint64_t>(limit, (bytes_.size() * 8 - bit_) / field.bits);
  }

  // The next value of `field` as a number (strings are read past: 0).
  double next(const Field& field) {
    switch (field.encoding) {
      case Encoding::kInteger:
        return static_cast<double>(field.minimum + static_cast<std::int64_t>(take(field.bits)));
      case Encoding::kScaledInteger:
        return static_cast<double>(field.minimum + static_cast<std::int64_t>(take(field.bits))) * field.scale +
               field.offset;
      case Encoding::kFloat:
        if (field.single_precision) return std::bit_cast<float>(static_cast<std::uint32_t>(take(32)));
        return std::bit_cast<double>(take(64));
      case Encoding::kString:
        skipString();
        return 0.0;
    }
    return 0.0;
  }

 private:
  // `bits` (<= 64) bits, least significant first.
  std::uint64_t take(unsigned bits) {
    std::uint64_t value = 0;
    unsigned got = 0;
    while (got < bits) {
      const unsigned in_byte = static_cast<unsigned>(bit_ % 8);
      const unsigned n = std::min(8u - in_byte, bits - got);
      const std::uint64_t part = (std::to_integer<std::uint64_t>(bytes_[bit_ / 8]) >> in_byte) & ((1u << n) - 1u);
      value |= part << got;
      got += n;
      bit_ += n;
    }
    return value;
  }

  // A string's length prefix at byte `at`: (prefix bytes, string bytes), or nothing if incomplete.
  std::optional<std::pair<std::size_t, std::uint64_t>> prefixAt(std::size_t at) const {
    if (at >= bytes_.size()) return std::nullopt;
    const auto first = std::to_integer<std::uint64_t>(bytes_[at]);
    if ((first & 1u) == 0) return std::pair<std::size_t, std::uint64_t>{1, first >> 1};
    if (at + 8 > bytes_.size()) return std::nullopt;
    return std::pair<std::size_t, std::uint64_t>{8, loadLittleEndian<std::uint64_t>(bytes_.data() + at) >> 1};
  }

  std::uint64_t stringsAvailable(std::uint64_t limit) const {
    std::uint64_t count = 0;
    std::size_t at = (bit_ + 7) / 8;
    while (count < limit) {
      const auto prefix = prefixAt(at);
      if (!prefix || prefix->second > bytes_.size() - at - prefix->first) break;
      at += prefix->first + prefix->second;
      ++count;
    }
    return count;
  }

  void skipString() {
    std::size_t at = (bit_ + 7) / 8;
    const auto prefix = prefixAt(at);
    bit_ = (at + prefix->first + prefix->second) * 8;
  }

  std::vector<std::byte> bytes_;
  std::uint64_t bit_ = 0;
};

// ---- The reader ----------------------------------------------------------------------------

class E57Reader final : public PointReader {
 public:
  static constexpr std::uint64_t kRecordsAtOnce = 1 << 16;  // decoded per call, so memory stays bounded

  explicit E57Reader(const std::string& path) : PointReader(path), file_(path) {
    const std::string xml_text = file_.readXml();
    pugi::xml_document document;
    const pugi::xml_parse_result parsed = document.load_buffer(xml_text.data(), xml_text.size());
    if (!parsed) {
      throw fileError(path, "XML section, byte " + std::to_string(parsed.offset) + " of it: " + parsed.description());
    }
    const XmlReader xml(file_);
    const pugi::xml_node root = document.child("e57Root");
    if (!root) throw xml.error("/", "no e57Root element");
    xml.typeOf(root, "/e57Root", "Structure");
    std::uint64_t declared = 0;
    if (const pugi::xml_node data3d = root.child("data3D")) {
      xml.typeOf(data3d, "/data3D", "Vector");
      for (const pugi::xml_node& child : data3d.children()) {
        if (child.type() != pugi::node_element) continue;
        // PointRecord::scan is 16 bits.
        if (scans_.size() > std::numeric_limits<std::uint16_t>::max()) {
          throw xml.error("/data3D", "more than 65536 scans; Plumb keeps at most 65536 per cloud");
        }
        scans_.push_back(readScan(xml, child, scans_.size()));
        declared += scans_.back().records;
      }
    }
    std::size_t images = 0;
    if (const pugi::xml_node images2d = root.child("images2D")) {
      for (const pugi::xml_node& child : images2d.children()) images += child.type() == pugi::node_element ? 1u : 0u;
    }

    info_.format = "E57 " + std::to_string(file_.versionMajor()) + "." + std::to_string(file_.versionMinor()) + ", " +
                   std::to_string(scans_.size()) + (scans_.size() == 1 ? " scan" : " scans");
    info_.declared_points = declared;
    for (const Scan& scan : scans_) info_.scans.push_back(scan.name);
    auto all = [&](Role role) {
      return !scans_.empty() && std::all_of(scans_.begin(), scans_.end(), [&](const Scan& s) { return s.has(role); });
    };
    info_.attributes.colour = all(Role::kRed) && all(Role::kGreen) && all(Role::kBlue);
    info_.attributes.intensity = all(Role::kIntensity);
    info_.attributes.normals = all(Role::kNormalX) && all(Role::kNormalY) && all(Role::kNormalZ);
    std::vector<std::string> ignored;
    for (const Scan& scan : scans_) {
      for (std::size_t f = 0; f < scan.fields.size(); ++f) {
        const Role role = roleOf(scan.fields[f].name);
        // An attribute only some scans have is left out of all: the others would have none to give.
        const bool partial = (isColour(role) && !info_.attributes.colour) ||
                             (isIntensity(role) && !info_.attributes.intensity) ||
                             (isNormal(role) && !info_.attributes.normals);
        if (role != Role::kIgnored && !partial) continue;
        const std::string entry = scan.fields[f].name + (partial ? " (not in every scan)" : "");
        if (std::find(ignored.begin(), ignored.end(), entry) == ignored.end()) ignored.push_back(entry);
      }
    }
    info_.ignored_fields = std::move(ignored);
    if (images > 0) info_.ignored_fields.push_back("images2D (" + std::to_string(images) + " images)");
  }

  bool read(PointBatch& batch, std::size_t max_points) override {
    batch.clear();
    while (batch.size() < max_points) {
      if (next_pending_ < pending_.size()) {
        deliver(batch, pending_[next_pending_],
                info_.attributes.normals ? pending_normals_[next_pending_] : std::array<float, 3>{});
        ++next_pending_;
        continue;
      }
      if (!decodeMore()) break;
    }
    return !batch.empty();
  }

 private:
  static bool isColour(Role role) {
    return role == Role::kRed || role == Role::kGreen || role == Role::kBlue || role == Role::kColourInvalid;
  }
  static bool isIntensity(Role role) { return role == Role::kIntensity || role == Role::kIntensityInvalid; }
  static bool isNormal(Role role) { return role == Role::kNormalX || role == Role::kNormalY || role == Role::kNormalZ; }

  // Decodes the next packet's records into pending_; false when every scan is done.
  bool decodeMore() {
    pending_.clear();
    pending_normals_.clear();
    next_pending_ = 0;
    while (pending_.empty()) {
      if (scan_ == scans_.size()) return false;
      const Scan& scan = scans_[scan_];
      if (!section_open_) openSection(scan);
      if (decoded_ == scan.records) {
        nextScan();
        continue;
      }
      // What the streams hold already first (fields of no bits need no packet at all).
      if (decodeRecords(scan) == 0) readPacket(scan);
    }
    return true;
  }

  void nextScan() {
    ++scan_;
    section_open_ = false;
    decoded_ = 0;
  }

  // The section header (section 9.3): sectionId 1, 7 reserved bytes, the section's logical
  // length, the physical offsets of its first data packet and of its index.
  void openSection(const Scan& scan) {
    streams_.assign(scan.fields.size(), Bytestream{});
    section_open_ = true;
    decoded_ = 0;
    // A scan without records may have no section at all (offset 0, the file header's place).
    if (scan.records == 0 && scan.section_offset == 0) return;
    const std::string what = scan.label + "'s compressed vector";
    const std::uint64_t start = file_.logicalOf(scan.section_offset, what + " offset");
    std::array<std::byte, 32> header;
    file_.read(start, header, what + " header");
    const auto id = std::to_integer<unsigned>(header[0]);
    if (id != 1) {
      throw file_.errorAt(scan.section_offset,
                          what + " header: section id " + std::to_string(id) + ", where a compressed vector has 1");
    }
    const auto length = loadLittleEndian<std::uint64_t>(header.data() + 8);
    const auto data_offset = loadLittleEndian<std::uint64_t>(header.data() + 16);
    section_end_ = start + length;
    if (length < header.size() || section_end_ > file_.logicalLength() || section_end_ < start) {
      throw file_.errorAt(scan.section_offset + 8,
                          what + ": its length " + std::to_string(length) + " runs past the end of the file");
    }
    if (scan.records == 0) return;  // writers leave the data offset of an empty section at 0
    // Each record takes at least the bits of its fields: a count the section cannot hold is
    // absurd, and so is one past 2^32 where the fields take none (every value the same).
    std::uint64_t record_bits = 0;
    for (const Field& field : scan.fields) record_bits += field.encoding == Encoding::kString ? 8 : field.bits;
    const std::uint64_t capacity = record_bits == 0 ? std::uint64_t{1} << 32 : length * 8 / record_bits;
    if (scan.records > capacity) {
      throw file_.errorAt(scan.section_offset + 8, what + ": " + std::to_string(scan.records) +
                                                       " records cannot fit in its " + std::to_string(length) +
                                                       " bytes");
    }
    packet_ = file_.logicalOf(data_offset, what + "'s data offset");
    if (packet_ < start + header.size() || packet_ >= section_end_) {
      throw file_.errorAt(scan.section_offset + 16, what + ": the first data packet (offset " +
                                                        std::to_string(data_offset) + ") lies outside the section");
    }
  }

  // One packet (section 9.4); a data packet's buffers go to the bytestreams, and the records they
  // complete are decoded.
  void readPacket(const Scan& scan) {
    const std::string what = scan.label + "'s packet";
    if (packet_ + 4 > section_end_) {
      throw file_.errorAtLogical(std::min(packet_, section_end_), "truncated: " + scan.label + " ends after " +
                                                                      std::to_string(decoded_) + " of " +
                                                                      std::to_string(scan.records) + " records");
    }
    std::array<std::byte, 4> head;
    file_.read(packet_, head, what + " header");
    const auto type = std::to_integer<unsigned>(head[0]);
    const std::uint64_t length = loadLittleEndian<std::uint16_t>(head.data() + 2) + std::uint64_t{1};
    if (packet_ + length > section_end_) {
      throw file_.errorAtLogical(packet_, what + " of " + std::to_string(length) + " bytes runs past its section");
    }
    const std::uint64_t at = packet_;
    packet_ += length;
    if (type == 0 || type == 2) return;  // an index or an empty packet
    if (type != 1) throw file_.errorAtLogical(at, what + " type " + std::to_string(type) + ": not 0, 1 or 2");

    packet_bytes_.resize(length);
    file_.read(at, packet_bytes_, what);
    if (length < 6) throw file_.errorAtLogical(at, what + ": a data packet of " + std::to_string(length) + " bytes");
    const std::size_t streams = loadLittleEndian<std::uint16_t>(packet_bytes_.data() + 4);
    if (streams != scan.fields.size()) {
      throw file_.errorAtLogical(at + 4, what + " has " + std::to_string(streams) + " bytestreams for " +
                                             std::to_string(scan.fields.size()) + " fields");
    }
    std::size_t offset = 6 + 2 * streams;
    if (offset > length) throw file_.errorAtLogical(at, what + ": its buffer lengths run past the packet");
    for (std::size_t s = 0; s < streams; ++s) {
      const std::size_t bytes = loadLittleEndian<std::uint16_t>(packet_bytes_.data() + 6 + 2 * s);
      if (offset + bytes > length) {
        throw file_.errorAtLogical(at + 6 + 2 * s, what + ": bytestream " + std::to_string(s) + " (" +
                                                       std::to_string(bytes) + " bytes) runs past the packet");
      }
      streams_[s].append(std::span(packet_bytes_).subspan(offset, bytes));
      offset += bytes;
    }
  }

  // Decodes the records the bytestreams hold whole, at most kRecordsAtOnce; returns how many.
  std::uint64_t decodeRecords(const Scan& scan) {
    std::uint64_t n = std::min(scan.records - decoded_, kRecordsAtOnce);
    for (std::size_t f = 0; f < scan.fields.size(); ++f) n = std::min(n, streams_[f].available(scan.fields[f], n));
    std::vector<double> values(scan.fields.size());
    const Eigen::Matrix3d rotation = scan.rotation.toRotationMatrix();
    for (std::uint64_t r = 0; r < n; ++r) {
      for (std::size_t f = 0; f < scan.fields.size(); ++f) values[f] = streams_[f].next(scan.fields[f]);
      auto value = [&](Role role) { return values[static_cast<std::size_t>(scan.field(role))]; };
      Eigen::Vector3d local;
      if (scan.has(Role::kX) && scan.has(Role::kY) && scan.has(Role::kZ)) {
        if (scan.has(Role::kCartesianInvalid) && value(Role::kCartesianInvalid) != 0.0) {
          ++counts_.non_finite;
          continue;
        }
        local = {value(Role::kX), value(Role::kY), value(Role::kZ)};
      } else {
        if (scan.has(Role::kSphericalInvalid) && value(Role::kSphericalInvalid) != 0.0) {
          ++counts_.non_finite;
          continue;
        }
        const double range = value(Role::kRange), azimuth = value(Role::kAzimuth), elevation = value(Role::kElevation);
        local = {range * std::cos(elevation) * std::cos(azimuth), range * std::cos(elevation) * std::sin(azimuth),
                 range * std::sin(elevation)};
      }
      const Eigen::Vector3d world = rotation * local + scan.translation;
      PointRecord point{world.x(), world.y(), world.z(), {0, 0, 0}, 0, static_cast<std::uint16_t>(scan_)};
      if (info_.attributes.intensity && !(scan.has(Role::kIntensityInvalid) && value(Role::kIntensityInvalid) != 0.0)) {
        point.intensity = normalised(value(Role::kIntensity), scan.intensity_limits, scan, Role::kIntensity);
      }
      if (info_.attributes.colour && !(scan.has(Role::kColourInvalid) && value(Role::kColourInvalid) != 0.0)) {
        const std::array<Role, 3> channels{Role::kRed, Role::kGreen, Role::kBlue};
        for (std::size_t c = 0; c < 3; ++c) {
          point.rgb[c] = normalised(value(channels[c]), scan.colour_limits[c], scan, channels[c]);
        }
      }
      pending_.push_back(point);
      if (info_.attributes.normals) {
        const Eigen::Vector3d normal =
            rotation * Eigen::Vector3d(value(Role::kNormalX), value(Role::kNormalY), value(Role::kNormalZ));
        pending_normals_.push_back(
            {static_cast<float>(normal.x()), static_cast<float>(normal.y()), static_cast<float>(normal.z())});
      }
    }
    decoded_ += n;
    return n;
  }

  // `v` on 0..65535 between the scan's limits for the quantity, else its field's bounds, else
  // 0..1 (a Float field without bounds).
  static std::uint16_t normalised(double v, const Limits& limits, const Scan& scan, Role role) {
    Limits range = limits;
    if (!range) range = scan.fields[static_cast<std::size_t>(scan.field(role))].bounds();
    if (!range || !(range->second > range->first)) range = std::pair{0.0, 1.0};
    const double t = std::clamp((v - range->first) / (range->second - range->first), 0.0, 1.0);
    return static_cast<std::uint16_t>(std::lround(t * 65535.0));
  }

  E57File file_;
  std::vector<Scan> scans_;
  std::size_t scan_ = 0;             // the scan being read
  bool section_open_ = false;        // its section header read
  std::uint64_t decoded_ = 0;        // its records decoded
  std::uint64_t packet_ = 0;         // logical offset of its next packet
  std::uint64_t section_end_ = 0;    // logical end of its section
  std::vector<Bytestream> streams_;  // one per field
  std::vector<std::byte> packet_bytes_;
  std::vector<PointRecord> pending_;  // decoded, not yet delivered
  std::vector<std::array<float, 3>> pending_normals_;
  std::size_t next_pending_ = 0;
};

}  // namespace

std::unique_ptr<PointReader> openE57(const std::string& path) {
  return std::make_unique<E57Reader>(path);
}

}  // namespace plumb::io
