// plumb view: the desktop viewer (ui/viewer), or its headless demo where no display answers.

#include <CLI/CLI.hpp>
#include <filesystem>
#include <memory>

#include "engine/core/error.h"
#include "engine/view/camera_json.h"
#include "ui/cli/clip_options.h"
#include "ui/cli/command.h"
#include "ui/viewer/demo_scan.h"
#include "ui/viewer/headless_demo.h"
#include "ui/viewer/project_session.h"
#include "ui/viewer/viewer_app.h"
#include "ui/viewer/window.h"

namespace plumb::cli {

Command addViewCommand(CLI::App& plumb) {
  auto options = std::make_shared<viewer::ViewerOptions>();
  auto clip = std::make_shared<ClipArguments>();
  auto camera = std::make_shared<std::string>();
  auto headless_out = std::make_shared<std::string>();
  CLI::App* sub =
      plumb.add_subcommand("view", "Open the viewer: fly through a cloud, click surfaces, watch their planes grow");
  sub->footer(
      "Without CLOUD it opens the demo, a simulated office scan made once into ~/.cache/plumb.\n"
      "Where no display answers it runs a headless demo instead: a grow on the demo scan, rendered to a PNG.\n"
      "Example: plumb view site.plumb   |   plumb view --script session.json --screenshot-dir shots");
  sub->add_option("cloud", options->cloud, "An octree (plumb import) or a point file (imported in the background)")
      ->check(CLI::ExistingFile);
  sub->add_option("--project", options->project,
                  "The project to open and save (.plumbproj; default: <CLOUD>.plumbproj, or the demo's in the cache); "
                  "its cloud and view are used unless CLOUD and --camera are given");
  sub->add_option("--script", options->script, "Replay a session script (docs/user-guide.md), then exit")
      ->check(CLI::ExistingFile);
  sub->add_option("--screenshot-dir", options->screenshot_dir, "Where the script's screenshots go (default .)");
  sub->add_option("--dump-scene", options->dump_scene, "Write the scene (segments, edges, corners) as JSON on exit");
  sub->add_option("--camera", *camera, "The first view: a camera JSON file (docs/camera-json.md)")
      ->check(CLI::ExistingFile);
  sub->add_option("--width", options->width, "Window width in pixels")
      ->check(CLI::Range(64, 16384))
      ->capture_default_str();
  sub->add_option("--height", options->height, "Window height in pixels")
      ->check(CLI::Range(64, 16384))
      ->capture_default_str();
  sub->add_option("--budget", options->budget_points,
                  "The most points a frame draws (default 1,000,000 on the CPU, else 5,000,000)")
      ->check(CLI::Range(std::uint64_t{10'000}, std::uint64_t{1'000'000'000}));
  sub->add_option("--render-scale", options->render_scale,
                  "Render the cloud at this fraction of the window's resolution (default 0.5 on the CPU, else 1)")
      ->check(CLI::Range(0.1, 1.0));
  sub->add_option("--tp", options->plane_threshold_m,
                  "The Grow tool's plane threshold t_p in metres, about 3 x the scanner's noise (the panel changes "
                  "it); by default each click measures the noise")
      ->check(CLI::Range(0.0005, 1.0))
      ->each([options](const std::string&) { options->plane_threshold_from_data = false; });
  sub->add_option("--autosave-s", options->autosave_s,
                  "Unsaved changes go to <project>.autosave at most this often (and when the viewer closes); "
                  "a session stopped by anything loses at most this much work")
      ->check(CLI::Range(0.1, 3600.0))
      ->capture_default_str();
  sub->add_option("--gpu", options->gpu, "The Vulkan device: cpu, discrete or a part of its name");
  addClipOptions(*sub, *clip);
  sub->add_flag("--xr", options->xr,
                "In a headset (OpenXR): the window mirrors the left eye; without a headset, the desktop as usual");
  sub->add_option("--xr-resolution", options->xr_resolution_scale,
                  "The eyes' resolution, a fraction of the headset's recommended size (default 1, 0.5 on the CPU)")
      ->check(CLI::Range(0.1, 1.0));
  sub->add_flag("!--fixed-quality", options->adaptive_quality,
                "Render a moving view as a still one (by default it drops resolution and points to keep 30 fps)");
  sub->add_flag("--real-time", options->script_wall_clock,
                "With --script: frames last what they take (dynamic resolution, double clicks, waits in ms); by "
                "default a script runs at 30 frames per second of its own clock and replays the same whatever the "
                "machine's load");
  sub->add_flag("--profile", options->profile,
                "With --script: time the splat and the resolve of each moving frame on the GPU and print them");
  sub->add_option("--headless-out", *headless_out,
                  "The headless demo's PNG (default: the cache directory's demo-view.png)");

  auto run = [options, camera, headless_out, clip]() -> int {
    if (!camera->empty()) options->camera = view::readCameraJson(*camera);
    options->clip = clipSettingsOf(*clip);
    // A project that cannot be opened stops here, display or none, and is left as it is.
    if (!options->project.empty()) viewer::ProjectSession::open(options->project, options->cloud);
    if (!viewer::WindowSystem::displayAvailable()) {
      if (!options->script.empty()) throw Error("--script needs a display (run it under xvfb-run)");
      const std::string out =
          headless_out->empty() ? (viewer::userCacheDirectory() / "demo-view.png").string() : *headless_out;
      return viewer::runHeadlessDemo(out, options->gpu);
    }
    return viewer::runViewer(*options);
  };
  return {sub, run};
}

}  // namespace plumb::cli
