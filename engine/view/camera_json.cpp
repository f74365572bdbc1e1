#include "engine/view/camera_json.h"

#include <algorithm>
#include <cassert>
#include <cerrno>
#include <climits>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <string_view>

#include "engine/core/atomic_file.h"
#include "engine/core/error.h"

namespace plumb::view {
namespace {

using Json = nlohmann::json;

constexpr std::string_view kFormat = "plumb-camera";
// The fields of the file that only a whole camera file has, then those of the camera itself.
constexpr const char* kFileFields[] = {"format", "version"};
constexpr const char* kCameraFields[] = {"projection",     "position", "target", "up",   "fov_deg",
                                         "ortho_height_m", "viewport", "near_m", "far_m"};

std::string readText(const std::string& path) {
  std::error_code ignored;
  if (std::filesystem::is_directory(path, ignored)) throw fileError(path, "is a directory, not a camera file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw fileError(path, "cannot open the camera file (" + systemErrorText(errno) + ")");
  std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  if (in.bad()) throw fileError(path, "cannot read the camera file (" + systemErrorText(errno) + ")");
  return text;
}

// Errors about one field: "'<path>': field '<field>': <what>".
Error fieldError(const std::string& path, std::string_view field, std::string_view what) {
  return fileError(path, "field '" + std::string(field) + "': " + std::string(what));
}

double number(const std::string& path, std::string_view field, const Json& value) {
  if (!value.is_number()) throw fieldError(path, field, std::string("expected a number, found ") + value.type_name());
  const double result = value.get<double>();
  if (!std::isfinite(result)) throw fieldError(path, field, "the number is not finite");
  return result;
}

Eigen::Vector3d vector3(const std::string& path, std::string_view field, const Json& value) {
  if (!value.is_array() || value.size() != 3) {
    throw fieldError(path, field, "expected an array of 3 numbers [x, y, z]");
  }
  Eigen::Vector3d result;
  for (Eigen::Index i = 0; i < 3; ++i) {
    result[i] = number(path, std::string(field) + "[" + std::to_string(i) + "]", value[static_cast<std::size_t>(i)]);
  }
  return result;
}

int pixelCount(const std::string& path, std::string_view field, const Json& value) {
  if (!value.is_number_integer()) {
    throw fieldError(path, field, std::string("expected a whole number of pixels, found ") + value.type_name());
  }
  const bool too_big = value.is_number_unsigned() && value.get<std::uint64_t>() > static_cast<std::uint64_t>(INT_MAX);
  const bool too_small = !value.is_number_unsigned() && value.get<std::int64_t>() < INT_MIN;
  if (too_big || too_small) throw fieldError(path, field, "the pixel count is out of range");
  return value.get<int>();
}

Json parse(const std::string& path, const std::string& text) {
  std::string last_key;
  try {
    // The callback only watches keys, so that an out-of-range number can name its field.
    return Json::parse(text, [&last_key](int depth, Json::parse_event_t event, Json& parsed) {
      if (event == Json::parse_event_t::key && depth == 1) last_key = parsed.get<std::string>();
      return true;
    });
  } catch (const Json::parse_error& error) {
    throw fileErrorAt(path, error.byte, std::string("not a JSON camera file: ") + error.what());
  } catch (const Json::out_of_range& error) {
    // nlohmann rejects numbers beyond the range of a double (such as 1e999) here.
    const std::string what = std::string("a number is not finite (") + error.what() + ")";
    if (last_key.empty()) throw fileError(path, what);
    throw fieldError(path, last_key, what);
  } catch (const Json::exception& error) {
    throw fileError(path, std::string("not a JSON camera file: ") + error.what());
  }
}

// An unknown field is an error, so that a misspelt name is not silently replaced by its default.
// `prefix` places the object in its file ("" for a camera file, "camera." inside a project).
void checkKnownFields(const std::string& path, const Json& json, const std::string& prefix, bool camera_file) {
  std::string known;
  const auto list = [&known](const char* field) { known += (known.empty() ? "" : ", ") + std::string(field); };
  if (camera_file) std::for_each(std::begin(kFileFields), std::end(kFileFields), list);
  std::for_each(std::begin(kCameraFields), std::end(kCameraFields), list);
  for (const auto& [key, value] : json.items()) {
    bool is_known = false;
    for (const char* field : kCameraFields) is_known = is_known || key == field;
    for (const char* field : kFileFields) is_known = is_known || (camera_file && key == field);
    if (!is_known) throw fieldError(path, prefix + key, "unknown field (known: " + known + ")");
  }
}

// The camera of an object whose fields checkKnownFields accepted.
Camera cameraFields(const std::string& path, const Json& json, const std::string& prefix) {
  Camera camera;
  for (const char* required : {"position", "target"}) {
    if (!json.contains(required)) {
      throw fieldError(path, prefix + required, "missing (a camera needs a position and a target)");
    }
  }
  camera.position = vector3(path, prefix + "position", json["position"]);
  camera.target = vector3(path, prefix + "target", json["target"]);
  if (const auto it = json.find("up"); it != json.end()) camera.up = vector3(path, prefix + "up", *it);
  if (const auto it = json.find("projection"); it != json.end()) {
    if (*it == "perspective") {
      camera.projection = Projection::kPerspective;
    } else if (*it == "orthographic") {
      camera.projection = Projection::kOrthographic;
    } else {
      throw fieldError(path, prefix + "projection",
                       "expected \"perspective\" or \"orthographic\", found " + it->dump());
    }
  }
  if (const auto it = json.find("fov_deg"); it != json.end()) camera.fov_deg = number(path, prefix + "fov_deg", *it);
  if (const auto it = json.find("ortho_height_m"); it != json.end()) {
    camera.ortho_height_m = number(path, prefix + "ortho_height_m", *it);
  }
  if (const auto it = json.find("viewport"); it != json.end()) {
    if (!it->is_array() || it->size() != 2) {
      throw fieldError(path, prefix + "viewport", "expected [width, height] in pixels");
    }
    camera.viewport_width_px = pixelCount(path, prefix + "viewport[0]", (*it)[0]);
    camera.viewport_height_px = pixelCount(path, prefix + "viewport[1]", (*it)[1]);
  }
  if (const auto it = json.find("near_m"); it != json.end()) camera.near_m = number(path, prefix + "near_m", *it);
  if (const auto it = json.find("far_m"); it != json.end()) camera.far_m = number(path, prefix + "far_m", *it);

  if (const auto problem = findCameraProblem(camera)) throw fieldError(path, prefix + problem->field, problem->what);
  return camera;
}

// Every field of a camera file but format and version, in the order of docs/camera-json.md (an
// ordered_json keeps it, for people reading the file).
nlohmann::ordered_json cameraObject(const Camera& camera) {
  const auto array3 = [](const Eigen::Vector3d& v) { return nlohmann::ordered_json::array({v.x(), v.y(), v.z()}); };
  nlohmann::ordered_json json;
  json["projection"] = camera.projection == Projection::kPerspective ? "perspective" : "orthographic";
  json["position"] = array3(camera.position);
  json["target"] = array3(camera.target);
  json["up"] = array3(camera.up);
  json["fov_deg"] = camera.fov_deg;
  json["ortho_height_m"] = camera.ortho_height_m;
  json["viewport"] = {camera.viewport_width_px, camera.viewport_height_px};
  json["near_m"] = camera.near_m;
  json["far_m"] = camera.far_m;
  return json;
}

}  // namespace

Camera readCameraJson(const std::string& path) {
  const Json json = parse(path, readText(path));
  if (!json.is_object()) {
    throw fileError(path, std::string("expected a JSON object (a Plumb camera file), found ") + json.type_name());
  }
  checkKnownFields(path, json, "", true);

  if (const auto it = json.find("format"); it != json.end()) {
    if (!it->is_string() || it->get<std::string>() != kFormat) {
      throw fieldError(path, "format", "expected \"plumb-camera\", found " + it->dump() + " (not a Plumb camera file)");
    }
  }
  if (const auto it = json.find("version"); it != json.end()) {
    // nlohmann stores non-negative whole numbers as unsigned and negative ones as signed.
    if (!it->is_number_integer() || !it->is_number_unsigned() || it->get<std::uint64_t>() == 0) {
      throw fieldError(path, "version", "expected a positive whole number, found " + it->dump());
    }
    const bool newer = it->get<std::uint64_t>() > static_cast<std::uint64_t>(kCameraJsonVersion);
    if (newer) {
      throw fieldError(path, "version",
                       "version " + it->dump() + " was written by a newer Plumb (this one reads version " +
                           std::to_string(kCameraJsonVersion) + "); update Plumb");
    }
  }
  return cameraFields(path, json, "");
}

void writeCameraJson(const Camera& camera, const std::string& path) {
  if (const auto problem = findCameraProblem(camera)) {
    throw fileError(path, "not writing an invalid camera: field '" + problem->field + "': " + problem->what);
  }
  nlohmann::ordered_json json;
  json["format"] = kFormat;
  json["version"] = kCameraJsonVersion;
  const nlohmann::ordered_json fields = cameraObject(camera);
  for (const auto& [key, value] : fields.items()) json[key] = value;
  // One field per line with compact arrays: easy to read and to edit by hand.
  std::string text = "{\n";
  for (const auto& [key, value] : json.items()) {
    if (text.size() > 2) text += ",\n";
    text += "  \"" + key + "\": " + value.dump();
  }
  text += "\n}\n";
  AtomicFile file(path);
  file.write(text.data(), text.size());
  file.commit();
}

std::string cameraJsonObject(const Camera& camera) {
  assert(!findCameraProblem(camera) && "cameraJsonObject of an invalid camera: check it with findCameraProblem");
  return cameraObject(camera).dump();
}

Camera cameraFromJsonObject(std::string_view object_text, const std::string& path, std::string_view field) {
  Json json;
  try {
    json = Json::parse(object_text);
  } catch (const Json::exception& error) {
    throw fieldError(path, field, std::string("not a JSON camera: ") + error.what());
  }
  if (!json.is_object()) {
    throw fieldError(path, field, std::string("expected a JSON object (a camera), found ") + json.type_name());
  }
  const std::string prefix = std::string(field) + ".";
  checkKnownFields(path, json, prefix, false);
  return cameraFields(path, json, prefix);
}

}  // namespace plumb::view
