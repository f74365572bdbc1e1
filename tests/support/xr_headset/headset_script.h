#pragma once
// The script the simulated headset plays: where the head and the hands are on each frame, what the
// controllers' inputs read, which session events happen, which frames are captured, and the
// headset's fixed properties. Read from the JSON file PLUMB_XR_HEADSET_SCRIPT names, at
// xrCreateInstance. Poses are in the LOCAL/STAGE space in OpenXR's convention (OpenXR 1.0
// specification, section 2.16 "Coordinate System": right-handed, +y up, -z forward). Every key is
// optional; unknown keys are errors.
//
//   {"refresh_hz": 90,                       frame period 1e9 / refresh_hz ns
//    "eye_size": [640, 480],                 recommended per-eye image size, 1 to 4096
//    "ipd_m": 0.064,
//    "fov_deg": {"left": -45, "right": 40, "up": 40, "down": -40},   the left eye's; the right
//                                            eye's is its mirror image (left = -right, right = -left)
//    "profile": "/interaction_profiles/oculus/touch_controller",     the controllers held
//    "capture": "all" | "none" | [frame indices],   frames read back to PNGs (default "all")
//    "capture_latest": false,                true: every frame's eyes also go to latest-eye-E.png,
//                                            replaced each frame (the last frame of a session of
//                                            unknown length); an eye's depth, when the
//                                            application gives one, goes to frame-NNNN-depth-E.pfm
//                                            and latest-depth-E.pfm (Portable Float Maps)
//    "after_last_frame": "exit" | "hold",    exit (the default): STOPPING after the last frame;
//                                            hold: the last frame repeats for ever
//    "frames": [                             default: one frame with the head at (0, 1.6, 0)
//      {"repeat": 10,                        frames this entry holds for (default 1)
//       "head": {"position": [x, y, z], "orientation": [x, y, z, w]},   or "look_at": [x, y, z]
//                                            instead of "orientation" (+y up); what an entry leaves
//                                            out keeps the previous entry's value
//       "right": {"aim": {pose as for the head}, "grip": {pose} (default: the aim pose),
//                 "trigger": 0..1, "squeeze": 0..1, "thumbstick": [x, y], "thumbstick_click",
//                 "a", "b", "x", "y", "menu": true/false},
//       "left": {...},                       a hand absent from an entry keeps its state, absent
//                                            from the start it is inactive; null makes it inactive;
//                                            a hand's first aim defaults to (+-0.2, 1.4, -0.3)
//                                            pointing down -z; inputs default to 0 and false
//       "event": "unfocus" | "focus" | "exit" | "lose"}]}   on the entry's first frame
//
// Without a script: the defaults above, frames for ever ("hold"), no controllers.

#include <cstdint>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "tests/support/xr_headset/pose_math.h"

namespace plumb::xr_headset {

// The script's mistakes, the message naming the JSON location ("frames[2].right.trigger: ...").
class ScriptError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

enum class Hand { kLeft = 0, kRight = 1 };
inline constexpr int kHandCount = 2;

// One controller's state on one frame. Absent from the script so far: inactive.
struct HandState {
  bool active = false;
  Pose aim;
  Pose grip;
  bool grip_follows_aim = true;  // until the script gives "grip", the grip pose is the aim pose
  float trigger = 0, squeeze = 0;
  float thumbstick_x = 0, thumbstick_y = 0;
  bool thumbstick_click = false, a = false, b = false, x = false, y = false, menu = false;
};

enum class ScriptEvent { kNone, kUnfocus, kFocus, kExit, kLose };

enum class AfterLastFrame {
  kExit,  // STOPPING after the last frame, then IDLE and EXITING once the application ends the session
  kHold,  // the last frame repeats forever
};

// Angles of the eye's frustum edges in radians, as XrFovf: left and down negative.
struct FieldOfView {
  double left = 0, right = 0, up = 0, down = 0;
};

// One entry of "frames": its state holds for `repeat` frames; its event happens on the first.
struct ScriptEntry {
  std::uint64_t first_frame = 0;
  std::uint64_t repeat = 1;
  Pose head;
  HandState hands[kHandCount];
  ScriptEvent event = ScriptEvent::kNone;
};

struct HeadsetScript {
  double refresh_hz = 90;
  std::uint32_t eye_width = 640, eye_height = 480;
  double ipd_m = 0.064;
  FieldOfView left_eye_fov;  // the right eye's is its mirror image
  std::string profile = "/interaction_profiles/oculus/touch_controller";
  bool capture_all = true;
  std::set<std::uint64_t> captured_frames;  // when not capture_all
  bool capture_latest = false;              // every frame's eyes as latest-eye-E.png too
  AfterLastFrame after_last_frame = AfterLastFrame::kExit;
  std::vector<ScriptEntry> entries;  // never empty

  // Frames the entries cover; frames past them repeat the last entry.
  std::uint64_t frameCount() const;
  const ScriptEntry& entryAt(std::uint64_t frame) const;
  // The event that happens on `frame`: an entry's event on its first frame only.
  ScriptEvent eventAt(std::uint64_t frame) const;
  bool captures(std::uint64_t frame) const;
  // eye 0 the left, 1 the right.
  FieldOfView eyeFov(std::uint32_t eye) const;
  // The time between frames in nanoseconds (XrDuration).
  std::int64_t framePeriodNs() const;
};

// The script without a file: a head standing still at (0, 1.6, 0) looking down -z, no controllers,
// frames forever, every frame captured (when PLUMB_XR_HEADSET_OUT asks for output at all).
HeadsetScript defaultHeadsetScript();

// Parses a script's JSON text. Throws ScriptError naming the JSON location of the first problem.
HeadsetScript parseHeadsetScript(const std::string& json_text);

// Reads and parses the file at `path`. Throws ScriptError whose message starts with the path.
HeadsetScript loadHeadsetScript(const std::string& path);

}  // namespace plumb::xr_headset
