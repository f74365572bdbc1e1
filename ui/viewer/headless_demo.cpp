#include "ui/viewer/headless_demo.h"

#include <cstdio>

#include "engine/gpu/device.h"
#include "engine/gpu/instance.h"
#include "engine/gpu/memory.h"
#include "engine/io/png_image.h"
#include "engine/lod/node_cache.h"
#include "engine/lod/octree.h"
#include "engine/render/point_renderer.h"
#include "engine/view/camera_controls.h"
#include "reco/data_at_click.h"
#include "reco/parameters.h"
#include "reco/region_grower.h"
#include "ui/viewer/demo_scan.h"
#include "ui/viewer/grow_session.h"
#include "ui/viewer/scene_overlay.h"
#include "ui/viewer/scene_state.h"
#include "ui/viewer/view_at_click.h"

namespace plumb::viewer {

int runHeadlessDemo(const std::string& png_path, const std::string& gpu_name) {
  std::printf("plumb view: no display here; running the headless demo instead\n");
  const DemoScan demo = ensureDemoScan([](std::string_view phase, double fraction) {
    std::fprintf(stderr, "\r  %.*s %3.0f %%   ", static_cast<int>(phase.size()), phase.data(), 100.0 * fraction);
  });
  std::fprintf(stderr, "\n");
  const auto octree = lod::Octree::open(demo.octree.string());
  lod::NodeCache cache(octree, std::size_t{1} << 30);

  // The demo's first view, 1280 x 720, and a click at the middle of the corridor's right wall.
  view::Camera camera = demo.home;
  camera.viewport_width_px = 1280;
  camera.viewport_height_px = 720;
  const Eigen::Vector3d wall_point(camera.position.x() + 2.4, camera.position.y() - 1.0, camera.position.z() - 0.3);
  const reco::GrowParameters parameters =
      reco::parametersForView(*viewAtClick(camera, wall_point), {}, reco::dataAtClick(cache, wall_point));
  const reco::GrowSnapshot result = reco::growRegions(cache, parameters);
  std::printf("  grew %zu segments, %zu edges and %zu corners in %.1f ms at the corridor wall\n",
              result.segments.size(), result.edges.size(), result.corners.size(), result.elapsed_ms);
  for (const reco::SegmentSnapshot& segment : result.segments) {
    std::printf("    %10llu points, normal %+.3f %+.3f %+.3f, rms %.2f mm\n",
                static_cast<unsigned long long>(segment.points), segment.plane.normal.x(), segment.plane.normal.y(),
                segment.plane.normal.z(), segment.plane.rms * 1e3);
  }

  SceneState scene;
  scene.applyGrow(GrowUpdate{1, parameters, result, true, -1.0});
  SceneOverlay overlay;
  const gpu::Instance instance(gpu::instanceOptionsFromEnvironment());
  const gpu::Device device(
      instance, gpu_name.empty() ? gpu::deviceChoiceFromEnvironment() : gpu::DeviceChoice{.prefer = gpu_name});
  gpu::MemoryAllocator allocator(device);
  render::PointRenderer renderer(device, allocator, cache);
  renderer.setOverlay(overlay.update(scene.registry()));
  renderer.renderComplete(camera, {});
  io::writePng(renderer.readColour(), png_path);
  std::printf("  rendered the result on %s: %s\n", device.name().c_str(), png_path.c_str());
  const auto messages = instance.validationMessages();
  for (const std::string& message : messages) std::fprintf(stderr, "plumb view: validation: %s\n", message.c_str());
  return messages.empty() ? 0 : 1;
}

}  // namespace plumb::viewer
