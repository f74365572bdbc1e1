// Parsing the simulated headset's script (headset_script.h). Every problem is reported with its
// JSON location, and unknown keys are errors: a typo must not silently leave a default in place.
// Poses follow the OpenXR 1.0 specification, section 2.16 "Coordinate System" (unit quaternions
// x, y, z, w); the field of view follows XrFovf (chapter 10 "Rendering", section "View and
// Projection State": angles in radians, left and down negative).

#include "tests/support/xr_headset/headset_script.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <initializer_list>
#include <iterator>
#include <nlohmann/json.hpp>

namespace plumb::xr_headset {
namespace {

using Json = nlohmann::json;

constexpr double kPi = 3.14159265358979323846;
constexpr std::uint32_t kMaxEyeSizePx = 4096;  // the view configuration's maximum (xrEnumerateViewConfigurationViews)
constexpr double kUnitTolerance = 1e-3;        // how far from 1 a written quaternion's length may be

double radians(double degrees) {
  return degrees * kPi / 180;
}

[[noreturn]] void fail(const std::string& where, const std::string& problem) {
  throw ScriptError(where + ": " + problem);
}

void expectObjectWithKeys(const Json& value, const std::string& where, std::initializer_list<const char*> keys) {
  if (!value.is_object()) fail(where, "expected an object");
  for (const auto& [key, ignored] : value.items()) {
    (void)ignored;
    if (std::none_of(keys.begin(), keys.end(), [&](const char* known) { return key == known; })) {
      fail(where, "unknown key '" + key + "'");
    }
  }
}

double number(const Json& value, const std::string& where) {
  if (!value.is_number()) fail(where, "expected a number");
  const double result = value.get<double>();
  if (!std::isfinite(result)) fail(where, "expected a finite number");
  return result;
}

double numberIn(const Json& value, const std::string& where, double low, double high) {
  const double result = number(value, where);
  if (result < low || result > high) {
    fail(where, std::to_string(result) + " is outside [" + std::to_string(low) + ", " + std::to_string(high) + "]");
  }
  return result;
}

std::uint64_t unsignedInteger(const Json& value, const std::string& where, std::uint64_t low, std::uint64_t high) {
  if (!value.is_number_integer() || (!value.is_number_unsigned() && value.get<std::int64_t>() < 0)) {
    fail(where, "expected a non-negative integer");
  }
  const auto result = value.get<std::uint64_t>();
  if (result < low || result > high) {
    fail(where, std::to_string(result) + " is outside [" + std::to_string(low) + ", " + std::to_string(high) + "]");
  }
  return result;
}

bool boolean(const Json& value, const std::string& where) {
  if (!value.is_boolean()) fail(where, "expected true or false");
  return value.get<bool>();
}

std::string string(const Json& value, const std::string& where) {
  if (!value.is_string()) fail(where, "expected a string");
  return value.get<std::string>();
}

std::vector<double> numbers(const Json& value, const std::string& where, std::size_t count) {
  if (!value.is_array() || value.size() != count)
    fail(where, "expected an array of " + std::to_string(count) + " numbers");
  std::vector<double> result;
  for (std::size_t i = 0; i < count; ++i) result.push_back(number(value[i], where + "[" + std::to_string(i) + "]"));
  return result;
}

Vec3 vec3(const Json& value, const std::string& where) {
  const std::vector<double> xyz = numbers(value, where, 3);
  return {xyz[0], xyz[1], xyz[2]};
}

Quat unitQuaternion(const Json& value, const std::string& where) {
  const std::vector<double> xyzw = numbers(value, where, 4);
  const double length = std::sqrt(xyzw[0] * xyzw[0] + xyzw[1] * xyzw[1] + xyzw[2] * xyzw[2] + xyzw[3] * xyzw[3]);
  if (std::abs(length - 1) > kUnitTolerance) {
    fail(where, "not a unit quaternion [x, y, z, w] (its length is " + std::to_string(length) + ")");
  }
  return {xyzw[0] / length, xyzw[1] / length, xyzw[2] / length, xyzw[3] / length};
}

// {"position": [x, y, z], "orientation": [x, y, z, w]} or "look_at": [x, y, z] instead of the
// orientation; what is absent keeps `previous`'s value.
Pose pose(const Json& value, const std::string& where, const Pose& previous) {
  expectObjectWithKeys(value, where, {"position", "orientation", "look_at"});
  Pose result = previous;
  if (value.contains("position")) result.position = vec3(value["position"], where + ".position");
  if (value.contains("orientation") && value.contains("look_at")) fail(where, "give either orientation or look_at");
  if (value.contains("orientation")) result.orientation = unitQuaternion(value["orientation"], where + ".orientation");
  if (value.contains("look_at")) {
    const std::optional<Quat> orientation = lookAt(result.position, vec3(value["look_at"], where + ".look_at"));
    if (!orientation) fail(where + ".look_at", "the target is at the position or straight above or below it");
    result.orientation = *orientation;
  }
  return result;
}

// Where a controller appears when the script does not say: held in front of the body, pointing forward.
HandState firstHandState(Hand hand) {
  HandState state;
  state.active = true;
  state.aim.position = {hand == Hand::kLeft ? -0.2 : 0.2, 1.4, -0.3};
  state.grip = state.aim;
  return state;
}

// A hand's entry; what it leaves out keeps `previous`'s value. null makes the hand inactive.
HandState hand(const Json& value, const std::string& where, const HandState& previous, Hand which) {
  if (value.is_null()) return HandState{};
  expectObjectWithKeys(
      value, where,
      {"aim", "grip", "trigger", "squeeze", "thumbstick", "thumbstick_click", "a", "b", "x", "y", "menu"});
  HandState state = previous.active ? previous : firstHandState(which);
  if (value.contains("aim")) state.aim = pose(value["aim"], where + ".aim", state.aim);
  if (value.contains("grip")) {
    state.grip = pose(value["grip"], where + ".grip", state.grip_follows_aim ? state.aim : state.grip);
    state.grip_follows_aim = false;
  }
  if (state.grip_follows_aim) state.grip = state.aim;
  if (value.contains("trigger"))
    state.trigger = static_cast<float>(numberIn(value["trigger"], where + ".trigger", 0, 1));
  if (value.contains("squeeze"))
    state.squeeze = static_cast<float>(numberIn(value["squeeze"], where + ".squeeze", 0, 1));
  if (value.contains("thumbstick")) {
    const std::vector<double> xy = numbers(value["thumbstick"], where + ".thumbstick", 2);
    for (std::size_t i = 0; i < 2; ++i) {
      if (std::abs(xy[i]) > 1) fail(where + ".thumbstick[" + std::to_string(i) + "]", "is outside [-1, 1]");
    }
    state.thumbstick_x = static_cast<float>(xy[0]);
    state.thumbstick_y = static_cast<float>(xy[1]);
  }
  const std::pair<const char*, bool HandState::*> buttons[] = {{"thumbstick_click", &HandState::thumbstick_click},
                                                               {"a", &HandState::a},
                                                               {"b", &HandState::b},
                                                               {"x", &HandState::x},
                                                               {"y", &HandState::y},
                                                               {"menu", &HandState::menu}};
  for (const auto& [key, member] : buttons) {
    if (value.contains(key)) state.*member = boolean(value[key], where + "." + key);
  }
  return state;
}

ScriptEvent event(const Json& value, const std::string& where) {
  const std::string name = string(value, where);
  if (name == "unfocus") return ScriptEvent::kUnfocus;
  if (name == "focus") return ScriptEvent::kFocus;
  if (name == "exit") return ScriptEvent::kExit;
  if (name == "lose") return ScriptEvent::kLose;
  fail(where, "unknown event '" + name + "' (expected unfocus, focus, exit or lose)");
}

void readFieldOfView(const Json& value, const std::string& where, FieldOfView& fov) {
  expectObjectWithKeys(value, where, {"left", "right", "up", "down"});
  const std::pair<const char*, double FieldOfView::*> edges[] = {{"left", &FieldOfView::left},
                                                                 {"right", &FieldOfView::right},
                                                                 {"up", &FieldOfView::up},
                                                                 {"down", &FieldOfView::down}};
  for (const auto& [key, member] : edges) {
    if (value.contains(key)) fov.*member = radians(numberIn(value[key], where + "." + key, -89, 89));
  }
  if (fov.left >= fov.right) fail(where, "left must be less than right");
  if (fov.down >= fov.up) fail(where, "down must be less than up");
}

void readCapture(const Json& value, const std::string& where, HeadsetScript& script) {
  if (value.is_string() && (value == "all" || value == "none")) {
    script.capture_all = value == "all";
    script.captured_frames.clear();
    return;
  }
  if (!value.is_array()) fail(where, "expected \"all\", \"none\" or an array of frame indices");
  script.capture_all = false;
  for (std::size_t i = 0; i < value.size(); ++i) {
    script.captured_frames.insert(
        unsignedInteger(value[i], where + "[" + std::to_string(i) + "]", 0, std::uint64_t{1} << 40));
  }
}

void readFrames(const Json& value, HeadsetScript& script) {
  if (!value.is_array() || value.empty()) fail("frames", "expected a non-empty array");
  script.entries.clear();
  Pose head = defaultHeadsetScript().entries.front().head;
  HandState hands[kHandCount];
  std::uint64_t next_frame = 0;
  for (std::size_t i = 0; i < value.size(); ++i) {
    const std::string where = "frames[" + std::to_string(i) + "]";
    const Json& entry = value[i];
    expectObjectWithKeys(entry, where, {"repeat", "head", "left", "right", "event"});
    ScriptEntry parsed;
    parsed.first_frame = next_frame;
    if (entry.contains("repeat")) parsed.repeat = unsignedInteger(entry["repeat"], where + ".repeat", 1, 1'000'000'000);
    if (entry.contains("head")) head = pose(entry["head"], where + ".head", head);
    if (entry.contains("left")) hands[0] = hand(entry["left"], where + ".left", hands[0], Hand::kLeft);
    if (entry.contains("right")) hands[1] = hand(entry["right"], where + ".right", hands[1], Hand::kRight);
    if (entry.contains("event")) parsed.event = event(entry["event"], where + ".event");
    parsed.head = head;
    std::copy(std::begin(hands), std::end(hands), std::begin(parsed.hands));
    next_frame += parsed.repeat;
    script.entries.push_back(parsed);
  }
}

}  // namespace

std::uint64_t HeadsetScript::frameCount() const {
  return entries.back().first_frame + entries.back().repeat;
}

const ScriptEntry& HeadsetScript::entryAt(std::uint64_t frame) const {
  // The last entry whose first frame is at or before `frame`; entries are sorted by first_frame.
  const auto after = std::upper_bound(entries.begin(), entries.end(), frame,
                                      [](std::uint64_t f, const ScriptEntry& entry) { return f < entry.first_frame; });
  return *std::prev(after);
}

ScriptEvent HeadsetScript::eventAt(std::uint64_t frame) const {
  const ScriptEntry& entry = entryAt(frame);
  return entry.first_frame == frame ? entry.event : ScriptEvent::kNone;
}

bool HeadsetScript::captures(std::uint64_t frame) const {
  return capture_all || captured_frames.contains(frame);
}

FieldOfView HeadsetScript::eyeFov(std::uint32_t eye) const {
  if (eye == 0) return left_eye_fov;
  return {-left_eye_fov.right, -left_eye_fov.left, left_eye_fov.up, left_eye_fov.down};
}

std::int64_t HeadsetScript::framePeriodNs() const {
  return std::llround(1e9 / refresh_hz);
}

HeadsetScript defaultHeadsetScript() {
  HeadsetScript script;
  script.left_eye_fov = {radians(-45), radians(40), radians(40), radians(-40)};
  script.after_last_frame = AfterLastFrame::kHold;
  ScriptEntry still;
  still.head.position = {0, 1.6, 0};
  script.entries.push_back(still);
  return script;
}

HeadsetScript parseHeadsetScript(const std::string& json_text) {
  Json root;
  try {
    root = Json::parse(json_text);
  } catch (const Json::parse_error& error) {
    throw ScriptError(std::string("not valid JSON: ") + error.what());
  }
  expectObjectWithKeys(root, "the script",
                       {"refresh_hz", "eye_size", "ipd_m", "fov_deg", "profile", "capture", "capture_latest",
                        "after_last_frame", "frames"});
  HeadsetScript script = defaultHeadsetScript();
  script.after_last_frame = AfterLastFrame::kExit;  // a script tells a story with an end
  if (root.contains("refresh_hz")) script.refresh_hz = numberIn(root["refresh_hz"], "refresh_hz", 1, 1000);
  if (root.contains("eye_size")) {
    const Json& size = root["eye_size"];
    if (!size.is_array() || size.size() != 2) fail("eye_size", "expected [width, height]");
    script.eye_width = static_cast<std::uint32_t>(unsignedInteger(size[0], "eye_size[0]", 1, kMaxEyeSizePx));
    script.eye_height = static_cast<std::uint32_t>(unsignedInteger(size[1], "eye_size[1]", 1, kMaxEyeSizePx));
  }
  if (root.contains("ipd_m")) script.ipd_m = numberIn(root["ipd_m"], "ipd_m", 0, 1);
  if (root.contains("fov_deg")) readFieldOfView(root["fov_deg"], "fov_deg", script.left_eye_fov);
  if (root.contains("profile")) {
    script.profile = string(root["profile"], "profile");
    if (script.profile.rfind("/interaction_profiles/", 0) != 0) {
      fail("profile", "expected a path starting with /interaction_profiles/");
    }
  }
  if (root.contains("capture")) readCapture(root["capture"], "capture", script);
  if (root.contains("capture_latest")) {
    script.capture_latest = boolean(root["capture_latest"], "capture_latest");
  }
  if (root.contains("after_last_frame")) {
    const std::string after = string(root["after_last_frame"], "after_last_frame");
    if (after != "exit" && after != "hold") fail("after_last_frame", "expected \"exit\" or \"hold\"");
    script.after_last_frame = after == "exit" ? AfterLastFrame::kExit : AfterLastFrame::kHold;
  }
  if (root.contains("frames")) readFrames(root["frames"], script);
  return script;
}

HeadsetScript loadHeadsetScript(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw ScriptError(path + ": cannot be read");
  const std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  try {
    return parseHeadsetScript(text);
  } catch (const ScriptError& error) {
    throw ScriptError(path + ": " + error.what());
  }
}

}  // namespace plumb::xr_headset
