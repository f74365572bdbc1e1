#include "ui/viewer/session_script.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <algorithm>
#include <array>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <string_view>

#include "cad/measurement.h"
#include "engine/core/error.h"

namespace plumb::viewer {
namespace {

using nlohmann::json;

int keyCode(const std::string& name) {
  if (name.size() == 1 && name[0] >= 'A' && name[0] <= 'Z') return GLFW_KEY_A + (name[0] - 'A');
  if (name.size() == 1 && name[0] >= 'a' && name[0] <= 'z') return GLFW_KEY_A + (name[0] - 'a');
  if (name.size() == 1 && name[0] >= '0' && name[0] <= '9') return GLFW_KEY_0 + (name[0] - '0');
  if (name.size() >= 2 && name[0] == 'F' && name.size() <= 3) {
    const int n = std::atoi(name.c_str() + 1);
    if (n >= 1 && n <= 12) return GLFW_KEY_F1 + n - 1;
  }
  static const std::map<std::string, int> kNamed{{"ESCAPE", GLFW_KEY_ESCAPE},
                                                 {"SPACE", GLFW_KEY_SPACE},
                                                 {"TAB", GLFW_KEY_TAB},
                                                 {"ENTER", GLFW_KEY_ENTER},
                                                 {"DELETE", GLFW_KEY_DELETE},
                                                 {"BACKSPACE", GLFW_KEY_BACKSPACE},
                                                 {"PERIOD", GLFW_KEY_PERIOD},
                                                 {"LEFT", GLFW_KEY_LEFT},
                                                 {"RIGHT", GLFW_KEY_RIGHT},
                                                 {"UP", GLFW_KEY_UP},
                                                 {"DOWN", GLFW_KEY_DOWN},
                                                 {"PAGE_UP", GLFW_KEY_PAGE_UP},
                                                 {"PAGE_DOWN", GLFW_KEY_PAGE_DOWN},
                                                 {"LEFT_SHIFT", GLFW_KEY_LEFT_SHIFT},
                                                 {"LEFT_CONTROL", GLFW_KEY_LEFT_CONTROL},
                                                 {"MINUS", GLFW_KEY_MINUS}};
  const auto it = kNamed.find(name);
  return it == kNamed.end() ? -1 : it->second;
}

class StepParser {
 public:
  StepParser(const std::string& path, std::size_t index, const json& step) : path_(path), index_(index), step_(step) {}

  [[noreturn]] void fail(const std::string& what) const {
    throw Error(path_ + ": step " + std::to_string(index_ + 1) + ": " + what);
  }

  std::array<double, 2> pixel(const char* field) const {
    const json& value = step_.at(field);
    if (!value.is_array() || value.size() != 2 || !value[0].is_number() || !value[1].is_number()) {
      fail(std::string("'") + field + "' must be [x, y] in window pixels");
    }
    const double x = value[0].get<double>(), y = value[1].get<double>();
    if (!std::isfinite(x) || !std::isfinite(y) || x < 0 || y < 0 || x > 1e5 || y > 1e5) {
      fail(std::string("'") + field + "' is outside any window");
    }
    return {x, y};
  }

  Eigen::Vector3d worldPoint(const json& value, const char* field) const {
    if (!value.is_array() || value.size() != 3 || !value[0].is_number() || !value[1].is_number() ||
        !value[2].is_number()) {
      fail(std::string("'") + field + "' must be [X, Y, Z] in world coordinates");
    }
    const Eigen::Vector3d point(value[0].get<double>(), value[1].get<double>(), value[2].get<double>());
    if (!point.allFinite()) fail(std::string("'") + field + "' must be finite");
    return point;
  }

  int button() const {
    const std::string name = step_.value("button", "left");
    if (name == "left") return GLFW_MOUSE_BUTTON_LEFT;
    if (name == "right") return GLFW_MOUSE_BUTTON_RIGHT;
    if (name == "middle") return GLFW_MOUSE_BUTTON_MIDDLE;
    fail("unknown button '" + name + "' (left, right or middle)");
  }

  double number(const char* field, double fallback, double min, double max) const {
    if (!step_.contains(field)) return fallback;
    const json& value = step_.at(field);
    if (!value.is_number()) fail(std::string("'") + field + "' must be a number");
    const double v = value.get<double>();
    if (!(v >= min && v <= max))
      fail(std::string("'") + field + "' must lie in [" + std::to_string(min) + ", " + std::to_string(max) + "]");
    return v;
  }

  ScriptStep parse() const {
    if (!step_.is_object() || step_.empty()) fail("a step is an object such as {\"click\": [x, y]}");
    ScriptStep out;
    out.line = index_;
    using Kind = InputEvent::Kind;
    const auto move = [](double x, double y) { return InputEvent{.kind = Kind::kMouseMove, .x = x, .y = y}; };
    const auto buttonEvent = [](double x, double y, int b, bool pressed) {
      return InputEvent{.kind = Kind::kMouseButton, .x = x, .y = y, .button = b, .pressed = pressed};
    };
    if (step_.contains("move")) {
      const auto [x, y] = pixel("move");
      out.frames = {{move(x, y)}};
    } else if (step_.contains("click")) {
      const auto [x, y] = pixel("click");
      const int b = button();
      // One frame each: ImGui 1.86 keeps input as state and would miss a press released at once.
      out.frames = {{move(x, y)}, {buttonEvent(x, y, b, true)}, {buttonEvent(x, y, b, false)}};
    } else if (step_.contains("double_click")) {
      const auto [x, y] = pixel("double_click");
      const int b = GLFW_MOUSE_BUTTON_LEFT;
      out.frames = {{move(x, y)},
                    {buttonEvent(x, y, b, true), buttonEvent(x, y, b, false)},
                    {buttonEvent(x, y, b, true), buttonEvent(x, y, b, false)}};
    } else if (step_.contains("click_world")) {
      out.kind = ScriptStep::Kind::kClickWorld;
      out.world = worldPoint(step_.at("click_world"), "click_world");
    } else if (step_.contains("drag_world")) {
      const json& value = step_.at("drag_world");
      if (!value.is_array() || value.size() != 2) fail("'drag_world' must be [[X, Y, Z], [X, Y, Z]]");
      out.kind = ScriptStep::Kind::kDragWorld;
      out.world = worldPoint(value[0], "drag_world[0]");
      out.target = worldPoint(value[1], "drag_world[1]");
      out.count = static_cast<std::uint64_t>(number("steps", 10, 1, 1000));
    } else if (step_.contains("move_world")) {
      out.kind = ScriptStep::Kind::kMoveWorld;
      out.world = worldPoint(step_.at("move_world"), "move_world");
    } else if (step_.contains("look")) {
      const json& value = step_.at("look");
      if (!value.is_object() || !value.contains("position") || !value.contains("target")) {
        fail("'look' must be {\"position\": [X, Y, Z], \"target\": [X, Y, Z]}");
      }
      out.kind = ScriptStep::Kind::kLook;
      out.world = worldPoint(value.at("position"), "look.position");
      out.target = worldPoint(value.at("target"), "look.target");
      if ((out.world - out.target).norm() < 1e-6) fail("'look' needs a target away from the position");
    } else if (step_.contains("drag")) {
      const json& value = step_.at("drag");
      if (!value.is_array() || value.size() != 4) fail("'drag' must be [x0, y0, x1, y1]");
      std::array<double, 4> p{};
      for (std::size_t i = 0; i < 4; ++i) {
        if (!value[i].is_number()) fail("'drag' must be [x0, y0, x1, y1]");
        p[i] = value[i].get<double>();
        if (!std::isfinite(p[i]) || p[i] < 0 || p[i] > 1e5) fail("'drag' is outside any window");
      }
      const int b = button();
      const auto steps = static_cast<int>(number("steps", 10, 1, 1000));
      out.frames.push_back({move(p[0], p[1])});
      out.frames.push_back({buttonEvent(p[0], p[1], b, true)});
      for (int i = 1; i <= steps; ++i) {
        const double t = static_cast<double>(i) / steps;
        out.frames.push_back({move(p[0] + t * (p[2] - p[0]), p[1] + t * (p[3] - p[1]))});
      }
      out.frames.push_back({buttonEvent(p[2], p[3], b, false)});
    } else if (step_.contains("wheel")) {
      const double amount = number("wheel", 0, -100, 100);
      const auto [x, y] = step_.contains("at") ? pixel("at") : std::array<double, 2>{-1, -1};
      std::vector<InputEvent> frame;
      if (x >= 0) frame.push_back(move(x, y));
      frame.push_back(InputEvent{.kind = Kind::kWheel, .x = x, .y = y, .wheel_y = amount});
      out.frames = {frame};
    } else if (step_.contains("key")) {
      const json& value = step_.at("key");
      if (!value.is_string()) fail("'key' must be a key name such as \"F\" or \"ESCAPE\"");
      const int code = keyCode(value.get<std::string>());
      if (code < 0) fail("unknown key '" + value.get<std::string>() + "'");
      const auto hold = static_cast<std::size_t>(number("hold_frames", 0, 0, 100000));
      out.frames.push_back({InputEvent{.kind = Kind::kKey, .key = code, .pressed = true}});
      for (std::size_t i = 0; i < hold; ++i) out.frames.push_back({});
      out.frames.push_back({InputEvent{.kind = Kind::kKey, .key = code, .pressed = false}});
    } else if (step_.contains("key_down") || step_.contains("key_up")) {
      // A key held across steps (Shift to lock a direction, Control to extend the selection).
      const bool down = step_.contains("key_down");
      const json& value = step_.at(down ? "key_down" : "key_up");
      const int code = value.is_string() ? keyCode(value.get<std::string>()) : -1;
      if (code < 0) fail("unknown key in '" + std::string(down ? "key_down" : "key_up") + "'");
      out.frames.push_back({InputEvent{.kind = Kind::kKey, .key = code, .pressed = down}});
    } else if (step_.contains("type")) {
      // Text as typed: each character a key press, its character and a release, one frame each.
      const json& value = step_.at("type");
      if (!value.is_string()) fail("'type' must be a string such as \"1.25\"");
      for (const char c : value.get<std::string>()) {
        if (static_cast<unsigned char>(c) >= 128 || c < 32) fail("'type' takes printable ASCII only");
        const int code = c == '.'   ? GLFW_KEY_PERIOD
                         : c == '-' ? GLFW_KEY_MINUS
                         : c == '/' ? GLFW_KEY_SLASH
                                    : keyCode(std::string(1, c));
        std::vector<InputEvent> frame;
        if (code >= 0) frame.push_back(InputEvent{.kind = Kind::kKey, .key = code, .pressed = true});
        frame.push_back(InputEvent{.kind = Kind::kCharacter, .codepoint = static_cast<std::uint32_t>(c)});
        if (code >= 0) frame.push_back(InputEvent{.kind = Kind::kKey, .key = code, .pressed = false});
        out.frames.push_back(std::move(frame));
      }
    } else if (step_.contains("tool")) {
      const std::string name = step_.at("tool").is_string() ? step_.at("tool").get<std::string>() : "";
      out.kind = ScriptStep::Kind::kTool;
      static constexpr std::array<std::pair<const char*, Tool>, 6> kTools{{{"navigate", Tool::kNavigate},
                                                                           {"grow", Tool::kGrow},
                                                                           {"measure", Tool::kMeasure},
                                                                           {"polygon", Tool::kPolygon},
                                                                           {"move", Tool::kMove},
                                                                           {"extrude", Tool::kExtrude}}};
      const auto it = std::find_if(kTools.begin(), kTools.end(), [&](const auto& t) { return name == t.first; });
      if (it == kTools.end()) fail("unknown tool '" + name + "' (navigate, grow, measure, polygon, move or extrude)");
      out.tool = it->second;
    } else if (step_.contains("measure")) {
      const std::string name = step_.at("measure").is_string() ? step_.at("measure").get<std::string>() : "";
      const std::optional<cad::MeasureKind> kind = cad::measureKindNamed(name);
      if (!kind) {
        fail("unknown measure '" + name + "' (distance, angle, point_to_plane, between_planes, height or area)");
      }
      out.kind = ScriptStep::Kind::kMeasure;
      out.measure = *kind;
    } else if (step_.contains("grow_detail")) {
      const std::string name = step_.at("grow_detail").is_string() ? step_.at("grow_detail").get<std::string>() : "";
      // In the Grow panel's order (GrowPanel::detail).
      static constexpr std::array<std::string_view, 6> kDetails{"view", "view-paper", "low", "medium", "high", "full"};
      const auto it = std::find(kDetails.begin(), kDetails.end(), name);
      if (it == kDetails.end())
        fail("unknown grow_detail '" + name + "' (view, view-paper, low, medium, high or full)");
      out.kind = ScriptStep::Kind::kGrowDetail;
      out.count = static_cast<std::uint64_t>(it - kDetails.begin());
    } else if (step_.contains("colour")) {
      const std::string name = step_.at("colour").is_string() ? step_.at("colour").get<std::string>() : "";
      // In the order of render::ColourMode.
      static constexpr std::array<std::string_view, 5> kColours{"auto", "rgb", "intensity", "elevation", "scan"};
      const auto it = std::find(kColours.begin(), kColours.end(), name);
      if (it == kColours.end()) fail("unknown colour '" + name + "' (auto, rgb, intensity, elevation or scan)");
      out.kind = ScriptStep::Kind::kColour;
      out.count = static_cast<std::uint64_t>(it - kColours.begin());
    } else if (step_.contains("wait")) {
      const std::string what = step_.at("wait").is_string() ? step_.at("wait").get<std::string>() : "";
      out.timeout_s = number("timeout_s", 60, 0.001, 3600);
      if (what == "frames") {
        out.kind = ScriptStep::Kind::kWaitFrames;
        out.count = static_cast<std::uint64_t>(number("count", 1, 0, 1e6));
      } else if (what == "ms") {
        out.kind = ScriptStep::Kind::kWaitMs;
        out.ms = number("ms", 0, 0, 3.6e6);
      } else if (what == "grower_idle") {
        out.kind = ScriptStep::Kind::kWaitGrowerIdle;
      } else if (what == "streaming_idle") {
        out.kind = ScriptStep::Kind::kWaitStreamingIdle;
      } else {
        fail("unknown wait '" + what + "' (frames, ms, grower_idle, streaming_idle)");
      }
    } else if (step_.contains("screenshot")) {
      out.kind = ScriptStep::Kind::kScreenshot;
      out.name = step_.at("screenshot").is_string() ? step_.at("screenshot").get<std::string>() : "";
      if (out.name.empty() || out.name.find('/') != std::string::npos || out.name.size() > 200) {
        fail("'screenshot' must be a file name (no folders; it goes into --screenshot-dir)");
      }
    } else if (step_.contains("memory")) {
      out.kind = ScriptStep::Kind::kMemory;
      out.name = step_.at("memory").is_string() ? step_.at("memory").get<std::string>() : "";
      if (out.name.size() > 200) fail("'memory' is a label of at most 200 characters");
    } else if (step_.contains("resize")) {
      const auto [w, h] = pixel("resize");
      if (w < 64 || h < 64 || w > 16384 || h > 16384) fail("'resize' must be from 64 x 64 to 16384 x 16384");
      out.kind = ScriptStep::Kind::kResize;
      out.width = static_cast<int>(w);
      out.height = static_cast<int>(h);
    } else {
      fail("unknown step " + step_.dump() + " (see docs/user-guide.md)");
    }
    return out;
  }

 private:
  const std::string& path_;
  std::size_t index_;
  const json& step_;
};

}  // namespace

std::vector<ScriptStep> readSessionScript(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw Error(path + ": cannot open the session script");
  json document;
  try {
    document = json::parse(in);
  } catch (const json::parse_error& error) {
    throw Error(path + ": not JSON: " + error.what());
  }
  const json* steps = &document;
  if (document.is_object() && document.contains("steps")) steps = &document.at("steps");
  if (!steps->is_array()) throw Error(path + ": expected a list of steps (or {\"steps\": [...]})");
  if (steps->size() > 100000) throw Error(path + ": more than 100000 steps");
  std::vector<ScriptStep> out;
  for (std::size_t i = 0; i < steps->size(); ++i) {
    try {
      out.push_back(StepParser(path, i, (*steps)[i]).parse());
    } catch (const json::exception& error) {
      throw Error(path + ": step " + std::to_string(i + 1) + ": " + error.what());
    }
  }
  return out;
}

ScriptPlayer::ScriptPlayer(std::vector<ScriptStep> steps, ScriptClock clock)
    : steps_(steps.begin(), steps.end()), clock_(clock) {}

ScriptFrame ScriptPlayer::next(bool grower_idle, bool streaming_idle) {
  ScriptFrame frame;
  // Steps that take no frame of their own (a tool, a screenshot) run together with the next.
  while (!steps_.empty()) {
    ScriptStep& step = steps_.front();
    const auto done = [&] {
      steps_.pop_front();
      frame_index_ = 0;
      frames_waited_ = 0;
      wait_started_.reset();
    };
    const auto waitedTooLong = [&] {
      if (!wait_started_) wait_started_ = Clock::now();
      return std::chrono::duration<double>(Clock::now() - *wait_started_).count() > step.timeout_s;
    };
    switch (step.kind) {
      case ScriptStep::Kind::kEvents:
        frame.events = step.frames[frame_index_];
        if (++frame_index_ >= step.frames.size()) done();
        return frame;
      case ScriptStep::Kind::kClickWorld:
        frame.click_world = step.world;
        done();
        return frame;
      case ScriptStep::Kind::kMoveWorld:
        frame.move_world = step.world;
        done();
        return frame;
      case ScriptStep::Kind::kDragWorld:
        frame.drag_world = ScriptFrame::WorldDrag{step.world, step.target, static_cast<int>(step.count)};
        done();
        return frame;
      case ScriptStep::Kind::kLook:
        frame.look = std::pair{step.world, step.target};
        done();
        return frame;
      case ScriptStep::Kind::kTool:
        frame.tool = step.tool;
        done();
        continue;
      case ScriptStep::Kind::kMeasure:
        frame.measure = step.measure;
        done();
        continue;
      case ScriptStep::Kind::kGrowDetail:
        frame.grow_detail = static_cast<int>(step.count);
        done();
        continue;
      case ScriptStep::Kind::kColour:
        frame.colour = static_cast<int>(step.count);
        done();
        continue;
      case ScriptStep::Kind::kScreenshot:
        frame.screenshot = step.name;
        done();
        return frame;  // one per frame: the copy is of this frame's image
      case ScriptStep::Kind::kMemory:
        frame.memory = step.name;
        done();
        continue;
      case ScriptStep::Kind::kResize:
        frame.resize = std::pair{step.width, step.height};
        done();
        return frame;
      case ScriptStep::Kind::kWaitFrames:
        if (frames_waited_++ < step.count) return frame;
        done();
        continue;
      case ScriptStep::Kind::kWaitMs:
        if (clock_ == ScriptClock::kScript) {
          if (static_cast<double>(frames_waited_++) * kScriptFrameMs < step.ms) return frame;
          done();
          continue;
        }
        if (!wait_started_) wait_started_ = Clock::now();
        if (std::chrono::duration<double, std::milli>(Clock::now() - *wait_started_).count() < step.ms) return frame;
        done();
        continue;
      case ScriptStep::Kind::kWaitGrowerIdle:
      case ScriptStep::Kind::kWaitStreamingIdle: {
        const bool idle = step.kind == ScriptStep::Kind::kWaitGrowerIdle ? grower_idle : streaming_idle;
        // At least one frame after the step before it, so a click's grow has started.
        if (frames_waited_++ == 0 || !idle) {
          if (waitedTooLong()) {
            frame.failure = "step " + std::to_string(step.line + 1) + ": the wait timed out after " +
                            std::to_string(step.timeout_s) + " s";
            return frame;
          }
          return frame;
        }
        done();
        continue;
      }
    }
  }
  // Steps at the end that take no frame of their own still run: the session ends on the next call.
  frame.finished = !frame.tool && !frame.grow_detail && !frame.colour && !frame.memory;
  return frame;
}

}  // namespace plumb::viewer
