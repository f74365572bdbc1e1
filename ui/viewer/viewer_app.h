#pragma once
// The desktop viewer (plumb view): a window on the cloud, navigation, the Dear ImGui palette,
// and live region growing on click. One main thread runs the frame loop; grows, node loads and
// imports run on the job system; their results come back as continuations drained once per
// frame, before the frame reads the scene.
//
//   frame: window events (or the script's) -> ImGui -> continuations (grow updates into the
//          ECS) -> tools and navigation -> palette -> overlay from the ECS -> render, present

#include <cstdint>
#include <optional>
#include <string>

#include "engine/view/clip_region.h"
#include "engine/view/camera.h"

namespace plumb::viewer {

struct ViewerOptions {
  std::string cloud;  // an octree or a point file (imported in the background); empty: the demo
  // The project (.plumbproj) to open and save; empty: defaultProjectPath (project_session.h), or
  // the demo's in the cache directory. Its cloud and camera are used unless `cloud` and `camera`
  // are given.
  std::string project;
  std::string script;  // a session script (session_script.h); empty: interactive
  // A script runs on its own clock, 30 frames a second whatever the machine's load, so that it
  // replays the same; the wall clock instead measures what navigation costs (benchmarks).
  bool script_wall_clock = false;
  std::string screenshot_dir;          // where the script's screenshots go
  std::string dump_scene;              // the scene as JSON when the viewer closes
  std::optional<view::Camera> camera;  // the first view; default: the demo's or an iso view of the cloud
  int width = 1280, height = 720;
  double autosave_s = 30.0;               // unsaved changes go to "<project>.autosave" at most this often
  double plane_threshold_m = 0.02;        // the Grow tool's t_p to begin with (its panel changes it)
  bool plane_threshold_from_data = true;  // t_p from the noise of each click's seed planes
  std::string gpu;                        // DeviceChoice::prefer; empty: PLUMB_GPU or automatic
  std::uint64_t budget_points = 0;        // 0: the device's default (lower on the CPU)
  double render_scale = 0.0;              // 0: the device's default (half resolution on the CPU)
  // Time the splat and the resolve of each moving frame on the GPU and print their medians at
  // the end of a scripted session (waits for each such frame: the frame rate drops a little).
  bool profile = false;
  // While the view moves, render fewer pixels and points to keep 30 frames per second.
  bool adaptive_quality = true;
  // What the view keeps of the cloud at first (--slice, --clip-box, ...); the View panel changes it.
  view::ClipSettings clip;
  // Start in a headset (OpenXR): its runtime makes the Vulkan device, the session begins at once
  // and the window mirrors the left eye. Without a runtime or a headset, one message and the
  // desktop as usual.
  bool xr = false;
  double xr_resolution_scale = 0.0;  // of the runtime's recommended eye size; 0: 1, or 0.5 on the CPU
};

// Runs the viewer until its window closes or its script ends. Returns the exit status: non-zero
// when a script step failed or the validation layer reported anything. Throws plumb::Error for
// what stops it from starting (no display, no Vulkan device, an unreadable cloud or script).
int runViewer(const ViewerOptions& options);

}  // namespace plumb::viewer
