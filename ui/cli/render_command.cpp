// plumb render: one image of a cloud, off screen, with no window system.

#include <CLI/App.hpp>
#include <CLI/Config.hpp>
#include <CLI/Formatter.hpp>
#include <chrono>
#include <cstdio>
#include <memory>

#include "engine/core/error.h"
#include "engine/gpu/device.h"
#include "engine/gpu/instance.h"
#include "engine/gpu/memory.h"
#include "engine/io/png_image.h"
#include "engine/lod/framing.h"
#include "engine/lod/node_cache.h"
#include "engine/lod/octree.h"
#include "engine/render/point_renderer.h"
#include "engine/view/camera_json.h"
#include "engine/view/view_presets.h"
#include "ui/cli/arguments.h"
#include "ui/cli/clip_options.h"
#include "ui/cli/cloud_input.h"
#include "ui/cli/command.h"

namespace plumb::cli {
namespace {

struct RenderOptions {
  std::string cloud;
  std::string camera;
  std::string view = "iso";
  std::string size;
  std::uint64_t budget = render::SelectionOptions{}.point_budget;
  std::string edl = "on";
  std::string splat = "surfel";
  std::string colour = "auto";
  std::string gpu;
  std::string output;
  ClipArguments clip;
};

// "1920x1080" -> {1920, 1080}; each side 1 to 16384.
std::array<int, 2> parseSize(const std::string& text) {
  const auto x = text.find('x');
  try {
    if (x != std::string::npos && x > 0 && x + 1 < text.size()) {
      std::size_t used_width = 0, used_height = 0;
      const int width = std::stoi(text.substr(0, x), &used_width);
      const int height = std::stoi(text.substr(x + 1), &used_height);
      if (used_width == x && used_height == text.size() - x - 1 && width >= 1 && height >= 1 && width <= 16384 &&
          height <= 16384) {
        return {width, height};
      }
    }
  } catch (const std::logic_error&) {
    // falls through to the error below
  }
  throw Error("--size " + text + ": expected WIDTHxHEIGHT, each from 1 to 16384 pixels");
}

render::ColourMode colourModeNamed(const std::string& name) {
  if (name == "auto") return render::ColourMode::kAuto;
  if (name == "rgb") return render::ColourMode::kRgb;
  if (name == "intensity") return render::ColourMode::kIntensity;
  if (name == "scan") return render::ColourMode::kScan;
  return render::ColourMode::kElevation;  // the CLI's check admits nothing else
}

}  // namespace

Command addRenderCommand(CLI::App& plumb) {
  auto options = std::make_shared<RenderOptions>();
  CLI::App* sub = plumb.add_subcommand("render", "Render a cloud to a PNG image off screen (Vulkan, no window needed)");
  sub->footer(
      "Example: plumb render site.plumb --view top --size 3840x2160 --budget 5000000 -o top.png\n"
      "A plan at 1.2 m: plumb render site.plumb --view top --slice 1.15,0.1 -o plan.png\n"
      "The GPU: a discrete one first, else lavapipe on the CPU; --gpu or PLUMB_GPU chooses (cpu, discrete or a "
      "part of the name).");
  sub->add_option("cloud", options->cloud, "An octree (plumb import) or a point file, imported on the fly")->required();
  auto* camera_option = sub->add_option("--camera", options->camera, "A camera JSON file (docs/camera-json.md)");
  sub->add_option("--view", options->view, "A standard view fitting the whole cloud (default iso)")
      ->check(CLI::IsMember({"top", "front", "side", "iso"}))
      ->excludes(camera_option);
  sub->add_option("--size", options->size,
                  "Image size WIDTHxHEIGHT in pixels (default 1920x1080, or the camera file's viewport)");
  sub->add_option("--budget", options->budget, "The most points drawn (default 2,000,000)")
      ->check(CLI::Range(std::uint64_t{1}, std::uint64_t{1'000'000'000}));
  sub->add_option("--edl", options->edl, "Eye-dome lighting (default on)")->check(CLI::IsMember({"on", "off"}));
  sub->add_option("--splat", options->splat,
                  "What each point covers: a disc in the plane of its surface (surfel, the default), a square "
                  "facing the eye (square) or its pixel (point, the fastest on lavapipe; surfaces show gaps up close)")
      ->check(CLI::IsMember({"surfel", "square", "point"}));
  // Segment colours need a labelling, which the viewer makes from its grows (SegmentLabels).
  sub->add_option("--colour", options->colour,
                  "Colour by rgb, intensity, elevation or scan (a colour per scan of a cloud that merges several; "
                  "default auto: rgb where the cloud has colour, else intensity, else elevation)")
      ->check(CLI::IsMember({"auto", "rgb", "intensity", "elevation", "scan"}));
  addClipOptions(*sub, options->clip);
  sub->add_option("--gpu", options->gpu, "The Vulkan device: cpu, discrete or a part of its name");
  sub->add_option("-o,--output", options->output, "The PNG to write")->required();

  auto run = [options]() -> int {
    view::Camera camera;
    std::array<int, 2> size{1920, 1080};
    if (!options->camera.empty()) {
      camera = view::readCameraJson(options->camera);
      size = {camera.viewport_width_px, camera.viewport_height_px};
    }
    if (!options->size.empty()) size = parseSize(options->size);
    const view::ClipRegion clip = clipSettingsOf(options->clip).region();

    const CloudInput cloud(options->cloud, "render");
    const lod::OctreeHeader& header = cloud.octree()->header();
    if (options->camera.empty()) {
      // The cloud's bulk, not its stray points (framing.h).
      const lod::Box3 framing = lod::framingBox(*cloud.octree());
      camera =
          view::presetCamera(*view::viewPresetNamed(options->view), {framing.min[0], framing.min[1], framing.min[2]},
                             {framing.max[0], framing.max[1], framing.max[2]}, size[0], size[1]);
    }
    camera.viewport_width_px = size[0];
    camera.viewport_height_px = size[1];
    view::validateCamera(camera);

    const gpu::Instance instance(gpu::instanceOptionsFromEnvironment());
    gpu::DeviceChoice choice =
        options->gpu.empty() ? gpu::deviceChoiceFromEnvironment() : gpu::DeviceChoice{.prefer = options->gpu};
    io::RgbaImage image;
    render::FrameStats stats;
    double seconds = 0.0;
    std::string device_name;
    {
      const gpu::Device device(instance, choice);
      device_name = device.name();
      gpu::MemoryAllocator allocator(device);
      lod::NodeCache nodes(cloud.octree(), std::size_t{1} << 30);
      render::PointRenderer renderer(device, allocator, nodes);
      render::RenderSettings settings;
      settings.selection.point_budget = options->budget;
      settings.edl = options->edl == "on";
      settings.splat = options->splat == "point"    ? render::SplatShape::kPoint
                       : options->splat == "square" ? render::SplatShape::kSquare
                                                    : render::SplatShape::kSurfel;
      settings.colour = colourModeNamed(options->colour);
      settings.clip = clip;
      const auto start = std::chrono::steady_clock::now();
      stats = renderer.renderComplete(camera, settings);
      image = renderer.readColour();
      seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    }
    const auto messages = instance.validationMessages();
    for (const std::string& message : messages)
      std::fprintf(stderr, "render: Vulkan validation: %s\n", message.c_str());
    if (!messages.empty())
      throw Error("the Vulkan validation layer reported " + std::to_string(messages.size()) +
                  " problems (above); no image written");

    io::writePng(image, options->output);
    std::printf("rendered %s of %s points (%s nodes, budget %s%s) at %d x %d on %s in %.2f s\n",
                withThousands(stats.points_drawn).c_str(), withThousands(header.point_count).c_str(),
                withThousands(stats.nodes_drawn).c_str(), withThousands(options->budget).c_str(),
                stats.budget_reached ? ", reached" : "", size[0], size[1], device_name.c_str(), seconds);
    std::printf("wrote %s\n", options->output.c_str());
    return 0;
  };
  return {sub, run};
}

}  // namespace plumb::cli
