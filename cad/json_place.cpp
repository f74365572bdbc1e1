#include "cad/json_place.h"

#include <cmath>
#include <limits>
#include <unordered_set>
#include <vector>

namespace plumb::cad {
namespace {

using Json = nlohmann::json;

std::string dumpShort(const Json& value) {
  std::string text = value.dump(-1, ' ', false, Json::error_handler_t::replace);
  constexpr std::size_t kMax = 40;
  if (text.size() > kMax) text = text.substr(0, kMax) + "...";
  return text;
}

// Where the parser is, kept from its callbacks, so that an error the parser throws without a
// place (a number too large for a double) can still name one.
class PlaceTracker {
 public:
  explicit PlaceTracker(const std::string& path) : path_(path) {}

  bool event(Json::parse_event_t event, const Json& parsed) {
    switch (event) {
      case Json::parse_event_t::object_start:
        frames_.push_back(Frame{false, {}, 0, {}});
        break;
      case Json::parse_event_t::array_start:
        frames_.push_back(Frame{true, {}, 0, {}});
        break;
      case Json::parse_event_t::object_end:
      case Json::parse_event_t::array_end:
        frames_.pop_back();
        elementDone();
        break;
      case Json::parse_event_t::key: {
        Frame& frame = frames_.back();
        frame.key = parsed.get<std::string>();
        // nlohmann would keep the last of two equal keys; a hand edit would then be lost silently.
        if (!frame.keys.insert(frame.key).second) {
          throw fileError(path_, "field '" + place() + "': the key appears twice in one object");
        }
        break;
      }
      case Json::parse_event_t::value:
        elementDone();
        break;
    }
    return true;
  }

  // The value being parsed: "segments[3].plane.normal[0]".
  std::string place() const {
    std::string text;
    for (const Frame& frame : frames_) {
      if (frame.array) {
        text += "[" + std::to_string(frame.next_index) + "]";
      } else {
        if (!text.empty()) text += ".";
        text += frame.key;
      }
    }
    return text;
  }

 private:
  struct Frame {
    bool array;
    std::string key;         // objects: the key of the value being parsed
    std::size_t next_index;  // arrays: the index of the element being parsed
    std::unordered_set<std::string> keys;
  };

  void elementDone() {
    if (!frames_.empty() && frames_.back().array) ++frames_.back().next_index;
  }

  const std::string& path_;
  std::vector<Frame> frames_;
};

}  // namespace

Json parseJsonFile(const std::string& path, const std::string& text, std::string_view what) {
  if (text.find_first_not_of(" \t\r\n") == std::string::npos) {
    throw fileError(path, "the file is empty (expected a " + std::string(what) + ")");
  }
  PlaceTracker tracker(path);
  try {
    return Json::parse(
        text, [&tracker](int, Json::parse_event_t event, Json& parsed) { return tracker.event(event, parsed); });
  } catch (const Json::parse_error& error) {
    throw fileErrorAt(path, error.byte, "not a JSON " + std::string(what) + ": " + error.what());
  } catch (const Json::out_of_range& error) {
    // nlohmann rejects numbers beyond the range of a double (such as 1e999) here.
    throw fileError(path, "field '" + tracker.place() + "': a number is not finite (" + error.what() + ")");
  } catch (const Json::exception& error) {
    throw fileError(path, "not a JSON " + std::string(what) + ": " + error.what());
  }
}

Error JsonPlace::error(std::string_view what) const {
  if (place_.empty()) return fileError(file_, what);
  return fileError(file_, "field '" + place_ + "': " + std::string(what));
}

void JsonPlace::expectObject(std::initializer_list<std::string_view> known) const {
  if (!value_.is_object()) throw error(std::string("expected an object, found ") + value_.type_name());
  for (const auto& [key, value] : value_.items()) {
    bool is_known = false;
    for (const std::string_view name : known) is_known = is_known || key == name;
    if (is_known) continue;
    std::string list;
    for (const std::string_view name : known) list += (list.empty() ? "" : ", ") + std::string(name);
    throw JsonPlace(file_, value, place_.empty() ? key : place_ + "." + key)
        .error("unknown field (known here: " + list + ")");
  }
}

JsonPlace JsonPlace::field(std::string_view name) const {
  if (auto found = optionalField(name)) return *found;
  throw JsonPlace(file_, value_, place_.empty() ? std::string(name) : place_ + "." + std::string(name))
      .error("missing (a required field)");
}

std::optional<JsonPlace> JsonPlace::optionalField(std::string_view name) const {
  if (!value_.is_object()) throw error(std::string("expected an object, found ") + value_.type_name());
  const auto it = value_.find(name);
  if (it == value_.end()) return std::nullopt;
  return JsonPlace(file_, *it, place_.empty() ? std::string(name) : place_ + "." + std::string(name));
}

std::size_t JsonPlace::expectArray(std::optional<std::size_t> size) const {
  if (!value_.is_array()) throw error(std::string("expected an array, found ") + value_.type_name());
  if (size && value_.size() != *size) {
    throw error("expected an array of " + std::to_string(*size) + " elements, found " + std::to_string(value_.size()));
  }
  return value_.size();
}

JsonPlace JsonPlace::element(std::size_t index) const {
  return JsonPlace(file_, value_.at(index), place_ + "[" + std::to_string(index) + "]");
}

double JsonPlace::number() const {
  if (!value_.is_number()) throw error(std::string("expected a number, found ") + value_.type_name());
  const double result = value_.get<double>();
  if (!std::isfinite(result)) throw error("the number is not finite");
  return result;
}

std::string JsonPlace::string() const {
  if (!value_.is_string()) throw error(std::string("expected a string, found ") + value_.type_name());
  return value_.get<std::string>();
}

std::uint64_t JsonPlace::whole(std::uint64_t min) const {
  // nlohmann stores non-negative whole numbers as unsigned, negative ones as signed, others as floats.
  if (!value_.is_number_unsigned() || value_.get<std::uint64_t>() < min) {
    throw error("expected a whole number of at least " + std::to_string(min) + ", found " + dumpShort(value_));
  }
  return value_.get<std::uint64_t>();
}

std::uint64_t JsonPlace::id() const {
  if (!value_.is_number_unsigned() || value_.get<std::uint64_t>() == 0) {
    throw error("expected an id, a positive whole number (0 means \"none\"), found " + dumpShort(value_));
  }
  return value_.get<std::uint64_t>();
}

std::uint32_t JsonPlace::index() const {
  const std::uint64_t value = whole();
  if (value > std::numeric_limits<std::uint32_t>::max()) throw error("the index is beyond 2^32 - 1");
  return static_cast<std::uint32_t>(value);
}

Eigen::Vector2d JsonPlace::vector2() const {
  if (!value_.is_array() || value_.size() != 2) throw error("expected an array of 2 numbers [u, v]");
  return {element(0).number(), element(1).number()};
}

Eigen::Vector3d JsonPlace::vector3() const {
  if (!value_.is_array() || value_.size() != 3) throw error("expected an array of 3 numbers [x, y, z]");
  return {element(0).number(), element(1).number(), element(2).number()};
}

}  // namespace plumb::cad
