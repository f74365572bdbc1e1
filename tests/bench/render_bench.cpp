// Renderer speed (docs/benchmarks.md). Prints, asserts nothing.
//
//   plumb_bench_render DIR [--points N] [--budgets A,B,..] [--size WxH] [--frames F] [--octree FILE]
//                          [--camera JSON]
//
// Builds an octree of a hall (the six faces of a 30 x 20 x 6 m box, N points, 6 million by
// default) in DIR, or opens FILE (a cloud of any size: the billion-point run of
// docs/benchmarks.md), and looks at it from the standard iso view, or the camera of JSON (as
// `plumb render --camera` reads it), at WxH (1920x1080). For each budget (1, 2 and 5 million
// points by default), once every node is on the GPU:
//   - the frame time: render() to the GPU's end of the frame, the median of F frames, with each
//     point a surfel (the default), and with each a square (Potree's adaptive point size);
//   - the splat and the resolve of the surfels in GPU time (timestamps);
//   - the surfels' estimate on the CPU (surfels.h, once per node on upload), in points per second;
//   - the splat again with one-pixel points (no adaptive point size), in points per second;
//   - the bare splat (shaders/bare_splat.comp.glsl) of the same points, as one flat array with
//     one transform, in points per second, and the one-pixel splat as a share of it.
// The device is PLUMB_GPU's choice: the GPU where there is one, lavapipe otherwise.

#include <CLI/App.hpp>
#include <CLI/Config.hpp>
#include <CLI/Formatter.hpp>
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "engine/core/huge_pages.h"
#include "engine/gpu/buffer.h"
#include "engine/gpu/commands.h"
#include "engine/gpu/compute_pipeline.h"
#include "engine/gpu/device.h"
#include "engine/gpu/instance.h"
#include "engine/gpu/memory.h"
#include "engine/gpu/timeline.h"
#include "engine/gpu/vk_check.h"
#include "engine/lod/framing.h"
#include "engine/lod/node_cache.h"
#include "engine/lod/octree.h"
#include "engine/render/node_selection.h"
#include "engine/render/point_renderer.h"
#include "engine/render/splat_transform.h"
#include "engine/render/surfel_estimates.h"
#include "engine/view/camera_json.h"
#include "engine/view/view_presets.h"
#include "shaders/render_layout.h"
#include "tests/support/generated_cloud.h"

namespace {

using namespace plumb;

constexpr std::uint32_t kBareSplat[] =
#include "shaders/bare_splat.comp.inc"
    ;

double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  return values[values.size() / 2];
}

// Point i of the hall: on one of its six faces, spread by area, with 5 mm of noise.
io::PointRecord hallPoint(std::uint64_t i) {
  constexpr double kX = 30.0, kY = 20.0, kZ = 6.0;
  const double areas[3] = {kX * kY, kX * kZ, kY * kZ};
  const double total = 2.0 * (areas[0] + areas[1] + areas[2]);
  const double pick = test::unitHash(i, 1) * total;
  const double u = test::unitHash(i, 2), v = test::unitHash(i, 3), noise = 0.005 * (test::unitHash(i, 4) - 0.5);
  const int face = pick < 2 * areas[0] ? 0 : pick < 2 * (areas[0] + areas[1]) ? 1 : 2;
  const bool far_side = test::unitHash(i, 5) < 0.5;
  double x, y, z;
  if (face == 0) {
    x = u * kX, y = v * kY, z = (far_side ? kZ : 0.0) + noise;
  } else if (face == 1) {
    x = u * kX, z = v * kZ, y = (far_side ? kY : 0.0) + noise;
  } else {
    y = u * kY, z = v * kZ, x = (far_side ? kX : 0.0) + noise;
  }
  const auto shade = static_cast<std::uint16_t>(20000 + 40000 * test::unitHash(i, 6));
  const std::array<std::uint16_t, 3> rgb =
      face == 0   ? std::array<std::uint16_t, 3>{shade, shade, shade}
      : face == 1 ? std::array<std::uint16_t, 3>{shade, static_cast<std::uint16_t>(shade / 2), 10000}
                  : std::array<std::uint16_t, 3>{10000, static_cast<std::uint16_t>(shade / 2), shade};
  return {512000.0 + x, 5403000.0 + y, 250.0 + z, rgb, shade};
}

// The bare splat of `points` (relative to `origin`), `repeat` times; the median GPU time in ms.
double bareSplatMs(const gpu::Device& device, gpu::MemoryAllocator& allocator,
                   const std::vector<lod::PackedPoint>& points, const view::Camera& camera,
                   const std::array<double, 3>& origin, int repeat) {
  const gpu::ComputePipeline pipeline(device, kBareSplat, sizeof(shader::BareSplatPush), "bare splat");
  gpu::Buffer point_buffer(device, allocator, points.size() * sizeof(lod::PackedPoint),
                           VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, gpu::kHostMemory, "bare points");
  std::memcpy(point_buffer.mapped(), points.data(), points.size() * sizeof(lod::PackedPoint));
  const auto pixels =
      static_cast<VkDeviceSize>(camera.viewport_width_px) * static_cast<VkDeviceSize>(camera.viewport_height_px);
  gpu::Buffer visibility(device, allocator, pixels * 8,
                         VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT, gpu::kDeviceMemory,
                         "bare visibility");
  const render::SplatTransform transform = render::splatTransform(camera, origin);
  shader::BareSplatPush push{};
  push.points = point_buffer.address();
  push.visibility = visibility.address();
  std::memcpy(push.clip_from_points, transform.clip_from_origin.data(), sizeof push.clip_from_points);
  std::memcpy(push.depth_from_points, transform.depth_from_origin.data(), sizeof push.depth_from_points);
  push.width = static_cast<std::uint32_t>(camera.viewport_width_px);
  push.height = static_cast<std::uint32_t>(camera.viewport_height_px);
  push.point_count = static_cast<std::uint32_t>(points.size());
  push.near_m = static_cast<float>(camera.near_m);

  VkQueryPoolCreateInfo query_info{};
  query_info.sType = VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO;
  query_info.queryType = VK_QUERY_TYPE_TIMESTAMP;
  query_info.queryCount = 2;
  VkQueryPool queries = VK_NULL_HANDLE;
  gpu::check(vkCreateQueryPool(device.handle(), &query_info, nullptr, &queries), "vkCreateQueryPool");
  gpu::TimelineSemaphore timeline(device);
  gpu::CommandPool pool(device, "bare splat");
  std::vector<double> times;
  for (int run = 0; run <= repeat; ++run) {  // run 0 warms up (lavapipe compiles at first use)
    pool.reset();
    VkCommandBuffer commands = pool.begin();
    vkCmdResetQueryPool(commands, queries, 0, 2);
    vkCmdFillBuffer(commands, visibility.handle(), 0, VK_WHOLE_SIZE, 0xFFFFFFFFu);
    gpu::memoryBarrier(commands, VK_PIPELINE_STAGE_2_CLEAR_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                       VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                       VK_ACCESS_2_SHADER_READ_BIT | VK_ACCESS_2_SHADER_WRITE_BIT);
    vkCmdWriteTimestamp2(commands, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, queries, 0);
    pipeline.dispatch(commands, push, (push.point_count + shader::kSplatGroupSize - 1) / shader::kSplatGroupSize);
    vkCmdWriteTimestamp2(commands, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, queries, 1);
    gpu::submit(device, commands, timeline, static_cast<std::uint64_t>(run + 1));
    timeline.wait(static_cast<std::uint64_t>(run + 1), ~std::uint64_t{0});
    std::uint64_t ticks[2] = {};
    gpu::check(vkGetQueryPoolResults(device.handle(), queries, 0, 2, sizeof ticks, ticks, sizeof ticks[0],
                                     VK_QUERY_RESULT_64_BIT),
               "vkGetQueryPoolResults");
    if (run > 0)
      times.push_back(static_cast<double>(ticks[1] - ticks[0]) * device.properties().limits.timestampPeriod * 1e-6);
  }
  vkDestroyQueryPool(device.handle(), queries, nullptr);
  return median(times);
}

}  // namespace

int main(int argc, char** argv) {
  plumb::runWithHugePageHeap(argv);  // as plumb runs
  CLI::App app("Renderer speed: frame time, splat and bare splat throughput (docs/benchmarks.md)");
  std::string directory;
  std::uint64_t point_count = 6'000'000;
  std::vector<std::uint64_t> budgets{1'000'000, 2'000'000, 5'000'000};
  std::string size = "1920x1080";
  int frames = 10;
  app.add_option("directory", directory, "Where the octree is built")->required();
  app.add_option("--points", point_count, "Points in the hall");
  app.add_option("--budgets", budgets, "Point budgets")->delimiter(',');
  app.add_option("--size", size, "WIDTHxHEIGHT");
  app.add_option("--frames", frames, "Frames timed per budget")->check(CLI::Range(1, 1000));
  std::string octree_path, camera_path;
  app.add_option("--octree", octree_path, "An octree to look at instead of the hall");
  app.add_option("--camera", camera_path, "A camera (JSON) to look through instead of the iso view");
  CLI11_PARSE(app, argc, argv);
  int width = 1920, height = 1080;
  if (std::sscanf(size.c_str(), "%dx%d", &width, &height) != 2 || width < 1 || height < 1) {
    std::fprintf(stderr, "--size %s: expected WIDTHxHEIGHT\n", size.c_str());
    return 2;
  }

  try {
    double build_s = 0.0;
    if (octree_path.empty()) {
      std::filesystem::create_directories(directory);
      lod::BuildOptions build;
      build.sources = {test::generatedSource(point_count, hallPoint)};
      build.output = (std::filesystem::path(directory) / "hall.plumb").string();
      const auto build_start = std::chrono::steady_clock::now();
      lod::buildOctree(build);
      build_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - build_start).count();
      octree_path = build.output;
    }
    const auto octree = lod::Octree::open(octree_path);
    point_count = octree->header().point_count;
    const lod::Box3 framing = lod::framingBox(*octree);
    view::Camera camera = view::presetCamera(view::ViewPreset::kIso, {framing.min[0], framing.min[1], framing.min[2]},
                                             {framing.max[0], framing.max[1], framing.max[2]}, width, height);
    if (!camera_path.empty()) {
      camera = view::readCameraJson(camera_path);
      camera.viewport_width_px = width;
      camera.viewport_height_px = height;
    }

    const gpu::Instance instance(gpu::instanceOptionsFromEnvironment());
    const gpu::Device device(instance, gpu::deviceChoiceFromEnvironment());
    gpu::MemoryAllocator allocator(device);
    std::printf("%s of %llu points (octree %.1f s, %llu nodes), %d x %d, %s, on %s\n", octree_path.c_str(),
                static_cast<unsigned long long>(point_count), build_s,
                static_cast<unsigned long long>(octree->header().node_count), width, height,
                camera_path.empty() ? "iso view" : camera_path.c_str(), device.name().c_str());
    std::printf("%10s %10s %10s %10s %10s %10s %10s %12s %12s %7s %12s\n", "budget", "points", "frame_ms", "splat_ms",
                "resolve_ms", "square_ms", "1px_splat", "1px_Mpt/s", "bare_Mpt/s", "share", "surfel_Mpt/s");
    for (const std::uint64_t budget : budgets) {
      lod::NodeCache nodes(octree, std::size_t{4} << 30);
      render::RendererOptions options;
      options.gpu_timing = true;
      options.gpu_budget_bytes = std::uint64_t{4} << 30;
      render::PointRenderer renderer(device, allocator, nodes, options);
      render::RenderSettings settings;
      settings.selection.point_budget = budget;
      render::FrameStats stats = renderer.renderComplete(camera, settings);
      // Frames as the viewer draws them; with squares instead of surfels; then the splat alone
      // with one-pixel points, the bare kernel's work, for the comparison.
      std::vector<double> frame_ms, splat_ms, resolve_ms, square_frame_ms, one_pixel_splat_ms;
      for (const render::SplatShape shape :
           {render::SplatShape::kSurfel, render::SplatShape::kSquare, render::SplatShape::kPoint}) {
        settings.splat = shape;
        for (int frame = 0; frame < frames + 1; ++frame) {  // the first frame warms up
          const auto start = std::chrono::steady_clock::now();
          stats = renderer.render(camera, settings);
          const render::GpuTimings timings = *renderer.gpuTimings();  // waits for the frame's end
          const double elapsed_ms =
              std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
          if (frame == 0) continue;
          if (shape == render::SplatShape::kPoint) {
            one_pixel_splat_ms.push_back(timings.splat_ms);
          } else if (shape == render::SplatShape::kSquare) {
            square_frame_ms.push_back(elapsed_ms);
          } else {
            frame_ms.push_back(elapsed_ms);
            splat_ms.push_back(timings.splat_ms);
            resolve_ms.push_back(timings.resolve_ms);
          }
        }
      }

      // The same points as one flat array relative to the cube's corner.
      const render::NodeSelection selection = render::selectNodes(*octree, camera, settings.selection);
      const std::array<double, 3> origin = octree->cube().origin;
      std::vector<lod::PackedPoint> flat;
      flat.reserve(selection.points);
      for (const lod::NodeInfo* info : selection.nodes) {
        const auto points = nodes.get(info->key);
        const std::array<double, 3> corner = octree->cube().cellMin(info->key);
        for (lod::PackedPoint p : points->points) {
          p.x = static_cast<float>(corner[0] - origin[0] + p.x);
          p.y = static_cast<float>(corner[1] - origin[1] + p.y);
          p.z = static_cast<float>(corner[2] - origin[2] + p.z);
          flat.push_back(p);
        }
      }
      const double bare_ms = bareSplatMs(device, allocator, flat, camera, origin, frames);
      // The surfels of the selected nodes, as their upload estimates them.
      const auto surfels_start = std::chrono::steady_clock::now();
      for (const lod::NodeInfo* info : selection.nodes) {
        render::nodeSurfels(*nodes.get(info->key), *render::nodeAncestors(nodes, info->key, true),
                            octree->cube().cellSize(info->key.level));
      }
      const double surfels_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - surfels_start).count();
      const double one_pixel = median(one_pixel_splat_ms);
      const double drawn = static_cast<double>(stats.points_drawn);
      std::printf("%10llu %10llu %10.2f %10.2f %10.2f %10.2f %10.2f %12.1f %12.1f %6.0f%% %12.1f\n",
                  static_cast<unsigned long long>(budget), static_cast<unsigned long long>(stats.points_drawn),
                  median(frame_ms), median(splat_ms), median(resolve_ms), median(square_frame_ms), one_pixel,
                  drawn / one_pixel / 1e3, static_cast<double>(flat.size()) / bare_ms / 1e3,
                  100.0 * (drawn / one_pixel) / (static_cast<double>(flat.size()) / bare_ms),
                  static_cast<double>(flat.size()) / surfels_s / 1e6);
    }
    // Figures taken while the validation layer reports a mistake are no figures: the run fails.
    const std::vector<std::string> messages = instance.validationMessages();
    for (const std::string& message : messages) std::fprintf(stderr, "validation: %s\n", message.c_str());
    if (!messages.empty()) return 1;
  } catch (const std::exception& error) {
    std::fprintf(stderr, "plumb_bench_render: %s\n", error.what());
    return 1;
  }
  return 0;
}
