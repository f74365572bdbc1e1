#pragma once
// Checked reading of a parsed JSON file, each value with its place in the file (a JSON path such
// as "polygons[2].vertices[1]"), so that every error names the file and the place.
//
// Internal to cad/: it includes nlohmann/json.hpp, so only cad's .cpp files include it.
// Errors are plumb::Error "'<file>': field '<place>': <what>", as for camera files.

#include <Eigen/Core>
#include <cstdint>
#include <initializer_list>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>

#include "engine/core/error.h"

namespace plumb::cad {

// `text` parsed as JSON. Throws plumb::Error naming `path` and: for an empty text, that it is
// empty; for a syntax error (NaN and truncation included), the byte offset; for a number beyond
// the range of a double, or a key repeated within one object, the place.
nlohmann::json parseJsonFile(const std::string& path, const std::string& text, std::string_view what);

// A value of the document and where it is. Holds references: the document and the path must
// outlive it.
class JsonPlace {
 public:
  JsonPlace(const std::string& file, const nlohmann::json& value, std::string place)
      : file_(file), value_(value), place_(std::move(place)) {}

  const nlohmann::json& value() const { return value_; }
  const std::string& place() const { return place_; }

  // "'<file>': field '<place>': <what>" (or "'<file>': <what>" for the document itself).
  Error error(std::string_view what) const;

  // Checks that the value is an object whose keys are all in `known`.
  void expectObject(std::initializer_list<std::string_view> known) const;
  // The field `name` of an object; missing is an error.
  JsonPlace field(std::string_view name) const;
  // The field `name` of an object, if it has one.
  std::optional<JsonPlace> optionalField(std::string_view name) const;

  // Checks that the value is an array (of exactly `size` elements unless nullopt); its size.
  std::size_t expectArray(std::optional<std::size_t> size = std::nullopt) const;
  JsonPlace element(std::size_t index) const;

  // The value as a finite number, a string, a whole number >= `min`, an index (a whole number
  // below 2^32), an id (a positive whole number: 0 means "none" and names no item), a vector of 2
  // or 3 numbers.
  double number() const;
  std::string string() const;
  std::uint64_t whole(std::uint64_t min = 0) const;
  std::uint32_t index() const;
  std::uint64_t id() const;
  Eigen::Vector2d vector2() const;
  Eigen::Vector3d vector3() const;

 private:
  const std::string& file_;
  const nlohmann::json& value_;
  std::string place_;
};

}  // namespace plumb::cad
