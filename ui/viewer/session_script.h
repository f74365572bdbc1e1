#pragma once
// Scripted sessions for tests and demos (plumb view --script): a JSON list of steps that the
// viewer replays as if a user did them, frame by frame, through the same InputEvents.
// docs/user-guide.md documents the format; in short, each step is one object:
//
//   {"move": [x, y]}                       the mouse to a window pixel
//   {"click": [x, y], "button": "left"}    press and release (button: left, right, middle)
//   {"double_click": [x, y]}
//   {"click_world": [X, Y, Z]}             a left click where a world point appears now
//   {"move_world": [X, Y, Z]}              the mouse to where a world point appears now
//   {"drag_world": [[X, Y, Z], [X, Y, Z]], "steps": 10}   a left drag between where two world
//                                          points appear now (a clip box's handle)
//   {"look": {"position": [X, Y, Z], "target": [X, Y, Z]}}   the camera, level (the viewport stays)
//   {"drag": [x0, y0, x1, y1], "button": "left", "steps": 10}
//   {"wheel": 1.0, "at": [x, y]}           positive zooms in
//   {"key": "F", "hold_frames": 0}         a key press and release (GLFW key names: A-Z, 0-9,
//                                          ESCAPE, SPACE, TAB, ENTER, DELETE, PAGE_UP, F1-F12, ...)
//   {"key_down": "LEFT_SHIFT"} | {"key_up": "LEFT_SHIFT"}   a key held across steps
//   {"type": "1.25"}                       text, a key and its character per frame
//   {"tool": "grow"}                       choose a tool (navigate, grow, measure, polygon, move,
//                                          extrude)
//   {"measure": "height"}                  the Measure tool, taking this kind (distance, angle,
//                                          point_to_plane, between_planes, height, area)
//   {"grow_detail": "medium"}              the Grow panel's Detail (view, view-paper, low, medium,
//                                          high, full)
//   {"colour": "scan"}                     the View panel's Colour (auto, rgb, intensity,
//                                          elevation, scan)
//   {"wait": "frames", "count": N} | {"wait": "ms", "ms": N} | {"wait": "grower_idle"} |
//   {"wait": "streaming_idle"}             the last two time out after "timeout_s" (default 60)
//   {"screenshot": "name.png"}             into --screenshot-dir
//   {"resize": [w, h]}                     the window
//   {"memory": "label"}                    print what the session holds: resident memory, node
//                                          cache, GPU memory, undo history (soak runs)
//
// The session ends after the last step (the scene is dumped, the viewer exits).

#include <Eigen/Core>
#include <chrono>
#include <cstdint>
#include <deque>
#include <optional>
#include <string>
#include <vector>

#include "ui/viewer/components.h"
#include "ui/viewer/input_event.h"

namespace plumb::viewer {

struct ScriptStep {
  enum class Kind : std::uint8_t {
    kEvents,      // `frames`: the events of each frame in turn
    kClickWorld,  // `world`
    kMoveWorld,   // `world`
    kDragWorld,   // from `world` to `target` in `count` moves
    kLook,        // `world` (the eye), `target`
    kTool,        // `tool`
    kMeasure,     // `measure`: the Measure tool with this kind
    kGrowDetail,  // `count`: the Grow panel's Detail entry (GrowPanel::detail)
    kColour,      // `count`: the View panel's Colour, a render::ColourMode
    kWaitFrames,  // `count`
    kWaitMs,      // `ms`
    kWaitGrowerIdle,
    kWaitStreamingIdle,
    kScreenshot,  // `name`
    kResize,      // `width`, `height`
    kMemory,      // `name`: the label of the report
  };
  Kind kind = Kind::kEvents;
  std::vector<std::vector<InputEvent>> frames{};
  Eigen::Vector3d world = Eigen::Vector3d::Zero();
  Eigen::Vector3d target = Eigen::Vector3d::Zero();
  Tool tool = Tool::kGrow;
  cad::MeasureKind measure = cad::MeasureKind::kDistance;
  std::uint64_t count = 0;
  double ms = 0.0;
  double timeout_s = 60.0;
  std::string name{};
  int width = 0, height = 0;
  std::size_t line = 0;  // the step's index in the file, for messages
};

// Parses a session file. Throws plumb::Error naming the file and the step for anything wrong.
std::vector<ScriptStep> readSessionScript(const std::string& path);

// What the player wants done this frame beside the input events.
struct ScriptFrame {
  std::vector<InputEvent> events;
  std::optional<Tool> tool;
  std::optional<cad::MeasureKind> measure;  // the Measure tool, taking this kind
  std::optional<int> grow_detail;           // the Grow panel's Detail entry
  std::optional<int> colour;                // the View panel's Colour, a render::ColourMode
  std::optional<std::string> screenshot;    // file name
  std::optional<std::pair<int, int>> resize;
  std::optional<std::string> memory;           // print a memory report with this label
  std::optional<Eigen::Vector3d> click_world;  // the viewer turns it into a click at its pixel
  std::optional<Eigen::Vector3d> move_world;   // ... a mouse move to its pixel
  struct WorldDrag {
    Eigen::Vector3d from, to;
    int steps = 10;
  };
  std::optional<WorldDrag> drag_world;  // ... a left drag between their pixels, in this frame
  std::optional<std::pair<Eigen::Vector3d, Eigen::Vector3d>> look;  // eye and target
  bool finished = false;                                            // every step is done
  std::optional<std::string> failure;                               // a wait timed out: the session fails
};

// A scripted session runs on the script's clock: each frame lasts kScriptFrameMs for everything
// the viewer times (double clicks, fly moves, Dear ImGui, dynamic resolution, "wait ms"), so a
// replay does the same, frame for frame, whatever the machine's load. The wall clock instead
// (ScriptClock::kWall) is for measuring what navigation costs; waits' timeouts always use it.
constexpr double kScriptFrameMs = 1000.0 / 30.0;
enum class ScriptClock : std::uint8_t { kScript, kWall };

class ScriptPlayer {
 public:
  explicit ScriptPlayer(std::vector<ScriptStep> steps, ScriptClock clock = ScriptClock::kScript);
  // The next frame's part of the script. `grower_idle`, `streaming_idle`: the viewer's state.
  ScriptFrame next(bool grower_idle, bool streaming_idle);

 private:
  using Clock = std::chrono::steady_clock;
  std::deque<ScriptStep> steps_;
  ScriptClock clock_;
  std::size_t frame_index_ = 0;  // in the front step's frames
  std::uint64_t frames_waited_ = 0;
  std::optional<Clock::time_point> wait_started_;
};

}  // namespace plumb::viewer
