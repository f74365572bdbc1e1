#pragma once
// The point cloud renderer: each frame selects octree nodes under a point budget
// (node_selection.h), streams missing ones to the GPU, splats them into a visibility buffer
// (shaders/splat.comp.glsl) and resolves colour with eye-dome lighting
// (shaders/resolve.comp.glsl), off screen; a window copies the colour into its swapchain.
//
// Frames are paced by a timeline semaphore: frame n waits for frame n - kFramesInFlight, and
// whatever a frame uses lives until the GPU has passed it (the deletion queue). A frame never
// waits for disk unless asked to (NodeLoading::kWait, for headless renders): a node not loaded
// yet is fetched by NodeCache's background jobs, and its parent, always drawn, stands in.
//
// Not thread-safe: one thread (the render thread) calls everything.

#include <vulkan/vulkan.h>

#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "engine/io/png_image.h"
#include "engine/lod/cell_key.h"
#include "engine/render/gpu_node_cache.h"
#include "engine/render/node_selection.h"
#include "engine/render/overlay_scene.h"
#include "engine/render/segment_labels.h"
#include "engine/view/clip_region.h"

namespace plumb::gpu {
class Device;
class MemoryAllocator;
struct SwapchainImage;
}  // namespace plumb::gpu
namespace plumb::lod {
class NodeCache;
}
namespace plumb::view {
struct Camera;
}

namespace plumb::render {

enum class ColourMode : std::uint8_t {
  kAuto,  // RGB where the cloud has colour, else intensity, else elevation
  kRgb,
  kIntensity,
  kElevation,
  kScan,  // a distinct colour per scan (lod::kHasScanIndex; a cloud of one scan has one colour)
  kSegment,
};

// What each point covers. Its size, the drawn cloud's spacing around it: the distance to its
// 4th nearest neighbour (surfels.h) scaled by the density of the level drawn there
// (splat_spacing.h).
enum class SplatShape : std::uint8_t {
  kPoint,   // its pixel alone (the bare splat's work, for the benchmark)
  kSquare,  // a square facing the eye (Potree's adaptive point size)
  kSurfel,  // a disc in the plane of its surface (surfels.h): closed surfaces, sharp edges
};

struct RenderSettings {
  ColourMode colour = ColourMode::kAuto;
  bool edl = true;
  float edl_strength = 0.35f;  // 1 is Potree's strength; scanner noise darkens dense surfaces then
  Rgba background{30, 32, 36, 255};
  SelectionOptions selection;
  SplatShape splat = SplatShape::kSurfel;
  // An overlay hides behind the cloud where it lies further than the cloud's point at its pixel
  // by more than this fraction of the depth plus 1 cm (scanner noise, polygons fitted to it).
  float overlay_depth_tolerance = 0.005f;
  // What is kept of the cloud (inactive: all of it); points cut away are neither drawn nor
  // picked. Must pass view::checkClipRegion.
  view::ClipRegion clip;
};

enum class NodeLoading : std::uint8_t {
  kStream,  // never block: draw what is on the GPU, fetch the rest in the background
  kWait,    // load every selected node before drawing (headless renders)
};

struct RendererOptions {
  std::uint64_t gpu_budget_bytes = std::uint64_t{768} << 20;  // resident node points
  std::uint64_t upload_ring_bytes = std::uint64_t{64} << 20;  // per frame at most this is uploaded
  bool gpu_timing = false;  // time the splat and the resolve with GPU timestamps (benchmarks)
  // Runs the surfels' estimates of streamed nodes (surfel_estimates.h) in the background (the
  // viewer's job system); empty: a task group of the renderer's own.
  std::function<void(std::function<void()> work)> background;
};

// GPU time of the last frame's passes (RendererOptions::gpu_timing).
struct GpuTimings {
  double splat_ms = 0.0;
  double resolve_ms = 0.0;
};

struct FrameStats {
  std::uint64_t frame = 0;
  std::uint64_t nodes_selected = 0;
  std::uint64_t nodes_drawn = 0;
  std::uint64_t nodes_missing = 0;  // selected but not on the GPU yet
  std::uint64_t points_selected = 0;
  std::uint64_t points_drawn = 0;
  std::uint64_t bytes_uploaded = 0;
  bool budget_reached = false;
  bool complete() const { return nodes_missing == 0; }
};

// The point under a pixel, from the last frame.
struct PickedPoint {
  std::array<double, 3> position;  // world coordinates, double precision
  lod::CellKey node;
  std::uint32_t index = 0;       // in the node's points
  int pixel_x = 0, pixel_y = 0;  // its own, or where that lies outside the window, the pixel it was found from
  float depth_m = 0.0f;          // its view depth, in front of the eye
};

class PointRenderer {
 public:
  static constexpr std::uint64_t kFramesInFlight = 2;

  PointRenderer(const gpu::Device& device, gpu::MemoryAllocator& allocator, lod::NodeCache& nodes,
                const RendererOptions& options = {});
  // Waits for the GPU to finish every frame.
  ~PointRenderer();
  PointRenderer(const PointRenderer&) = delete;
  PointRenderer& operator=(const PointRenderer&) = delete;

  // Renders one frame of the camera's viewport size off screen and copies it into each image of
  // `present_to` (acquired swapchain images: a window's, a headset's eye, or both when the window
  // mirrors the eye): the frame waits for the images' `acquired` semaphores and signals their
  // `rendered` ones (at most one image has them); the caller then presents. An image of the
  // frame's size and an RGBA8 format gets its bytes unchanged; another is scaled to fit, keeping
  // the aspect ratio, on the background colour. The camera must be valid. Throws
  // gpu::DeviceLost when the device is lost, plumb::Error for a corrupt node (kWait).
  // `choose_with`, when given, is the camera whose view chooses the nodes drawn instead of
  // `camera`: a headset's two eyes draw one selection (a view holding both), so that both show
  // the same detail.
  FrameStats render(const view::Camera& camera, const RenderSettings& settings,
                    NodeLoading loading = NodeLoading::kStream, std::span<const gpu::SwapchainImage> present_to = {},
                    const view::Camera* choose_with = nullptr);

  // Records more work into the frame's command buffer after the copy into the swapchain image:
  // a user interface drawn on top, a screenshot. The image arrives in TRANSFER_DST_OPTIMAL
  // with the copy's writes made available to the transfer stage; the hook must leave it in
  // PRESENT_SRC_KHR. Without a hook, or for an image not `decorated` (a headset's eye), the
  // renderer moves the image to its presented_layout itself. Set it before render(); null
  // removes it.
  using PresentHook = std::function<void(VkCommandBuffer commands, const gpu::SwapchainImage& image)>;
  void setPresentHook(PresentHook hook);

  // Blocks until the GPU has finished every frame submitted so far (a screenshot's readback).
  void waitForFrames();

  // The labelling ColourMode::kSegment shows (null: none, every point grey). Takes effect from
  // the next frame; nodes whose labels are not uploaded yet show grey meanwhile.
  void setSegmentLabels(std::shared_ptr<const SegmentLabels> labels);

  // What the overlay pass draws (null or empty: nothing). Takes effect from the next frame.
  void setOverlay(std::shared_ptr<const OverlayScene> overlay);

  // Renders with NodeLoading::kWait until every selected node is drawn (the upload ring may
  // take several frames for a big budget) and returns the last frame's stats.
  FrameStats renderComplete(const view::Camera& camera, const RenderSettings& settings);

  // Waits for the last frame and copies its colour out.
  io::RgbaImage readColour();

  // Waits for the last frame; the point under pixel (x, y) (rows from the top): the surface the
  // pixel nearest to it within `radius_px` shows of the front surface there (within 2 % plus
  // 2 cm of the nearest depth in that window; the nearer on a tie), and on it the point nearest,
  // among the points of the nodes the window shows; nothing when no point is there.
  std::optional<PickedPoint> pick(int x, int y, int radius_px = 3);

  // The last frame's target size, 0 x 0 before the first frame.
  std::array<std::uint32_t, 2> targetSize() const;

  // Waits for the last frame and reads its GPU timestamps; nothing without gpu_timing or
  // before the first frame.
  std::optional<GpuTimings> gpuTimings();

  // The nodes resident on the GPU, their bytes, uploads and evictions.
  GpuNodeCacheStats gpuNodeStats() const;

 private:
  struct Resources;
  std::unique_ptr<Resources> resources_;
};

}  // namespace plumb::render
