// One frame of the point renderer:
//   1. Pace: wait until the frame that last used this frame slot is done; run the deletions
//      and free the upload ring space of every finished frame.
//   2. Select nodes (node_selection.cpp); upload those not on the GPU that are loaded (or, with
//      NodeLoading::kWait, load them), as far as the upload ring has room.
//   3. Write the chunk table: per chunk of each drawn node its clip and depth transforms
//      (splat_transform.h).
//   4. Record: clear the visibility buffer, splat (the wide footprints listed by the splat then in
//      a pass of their own), resolve, draw the overlays, and blit into the swapchain image when
//      there is one; submit to signal the frame's value.
//   5. Evict resident nodes beyond the GPU budget.

#include "engine/render/point_renderer.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstring>
#include <limits>
#include <optional>
#include <span>
#include <string>

#include "engine/core/error.h"
#include "engine/gpu/buffer.h"
#include "engine/gpu/commands.h"
#include "engine/gpu/compute_pipeline.h"
#include "engine/gpu/deletion_queue.h"
#include "engine/gpu/device.h"
#include "engine/gpu/memory.h"
#include "engine/gpu/swapchain.h"
#include "engine/gpu/timeline.h"
#include "engine/gpu/upload_ring.h"
#include "engine/gpu/vk_check.h"
#include "engine/lod/node_cache.h"
#include "engine/render/depth_out_pass.h"
#include "engine/render/gpu_node_cache.h"
#include "engine/render/intensity_range.h"
#include "engine/render/overlay_pass.h"
#include "engine/render/render_target.h"
#include "engine/render/splat_spacing.h"
#include "engine/render/splat_transform.h"
#include "engine/render/surfel_estimates.h"
#include "engine/render/surfels.h"
#include "engine/view/camera.h"
#include "engine/view/camera_controls.h"
#include "shaders/render_layout.h"

namespace plumb::render {
namespace {

constexpr std::uint32_t kSplatCode[] =
#include "shaders/splat.comp.inc"
    ;
constexpr std::uint32_t kSplatWideCode[] =
#include "shaders/splat_wide.comp.inc"
    ;
constexpr std::uint32_t kResolveCode[] =
#include "shaders/resolve.comp.inc"
    ;

static_assert(sizeof(shader::SplatChunk) == 176, "SplatChunk differs from its std430 layout");
static_assert(sizeof(shader::SplatPush) == 72, "SplatPush differs from its std430 layout");
static_assert(sizeof(shader::WideSplatHeader) == 24, "WideSplatHeader differs from its std430 layout");
// The wide list's blocks: a point's id and a row, two words each, after the header.
constexpr VkDeviceSize kWideBlockBytes = 8;
static_assert(sizeof(shader::ResolvePush) == 72, "ResolvePush differs from its std430 layout");
static_assert(sizeof(lod::PackedPoint) == shader::kPointWords * 4, "the shaders read points as five words");

constexpr std::uint64_t kNoTimeout = std::numeric_limits<std::uint64_t>::max();

// Where a chunk's points came from, to map a picked id back to its point.
struct ChunkOrigin {
  lod::CellKey node;
  std::uint32_t first_point;
};

// kAuto becomes what the cloud has: colour, else intensity, else elevation.
ColourMode effectiveColourMode(ColourMode wanted, std::uint32_t attributes) {
  if (wanted != ColourMode::kAuto) return wanted;
  if (attributes & lod::kHasColour) return ColourMode::kRgb;
  if (attributes & lod::kHasIntensity) return ColourMode::kIntensity;
  return ColourMode::kElevation;
}

std::uint32_t shaderColourMode(ColourMode mode) {
  switch (mode) {
    case ColourMode::kRgb:
      return shader::kColourRgb;
    case ColourMode::kIntensity:
      return shader::kColourIntensity;
    case ColourMode::kElevation:
      return shader::kColourElevation;
    case ColourMode::kScan:
      return shader::kColourScan;
    default:
      return shader::kColourSegment;
  }
}

std::uint32_t shaderSplatShape(SplatShape shape) {
  switch (shape) {
    case SplatShape::kPoint:
      return shader::kSplatPoint;
    case SplatShape::kSquare:
      return shader::kSplatSquare;
    default:
      return shader::kSplatSurfel;
  }
}

// Copies the frame's colour into the swapchain image and leaves that ready to present. The
// colour image holds the colour already when the overlay pass ran or an earlier image of the
// frame took it; otherwise it comes from the colour buffer first.
void recordPresentation(VkCommandBuffer commands, const RenderTarget& target, const gpu::SwapchainImage& present,
                        bool colour_image_ready, const Rgba& background, const PointRenderer::PresentHook& hook) {
  const VkImage colour = target.colour_image.handle();
  if (!colour_image_ready) {
    target.copyColourToImage(commands, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT,
                             VK_ACCESS_2_TRANSFER_READ_BIT);
  } else {
    gpu::imageBarrier(commands, colour, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                      VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT | VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                      VK_ACCESS_2_TRANSFER_READ_BIT | VK_ACCESS_2_TRANSFER_WRITE_BIT,
                      VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_READ_BIT);
  }
  // The swapchain image: its old content is not needed; the acquire semaphore orders the write.
  gpu::imageBarrier(commands, present.image, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                    VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_NONE, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT,
                    VK_ACCESS_2_TRANSFER_WRITE_BIT);
  const bool same_size = present.extent.width == target.width && present.extent.height == target.height;
  const bool same_bytes = present.format == VK_FORMAT_R8G8B8A8_UNORM || present.format == VK_FORMAT_R8G8B8A8_SRGB;
  if (same_size && same_bytes) {
    // A copy, not a blit: an sRGB image (a headset's) takes the bytes, already sRGB-encoded.
    VkImageCopy copy{};
    copy.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    copy.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    copy.extent = {target.width, target.height, 1};
    vkCmdCopyImage(commands, colour, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, present.image,
                   VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &copy);
  } else {
    // Scaled to fit, centred: a window mirroring a headset's eye has another aspect ratio.
    const double scale = std::min(static_cast<double>(present.extent.width) / target.width,
                                  static_cast<double>(present.extent.height) / target.height);
    const auto width = static_cast<std::int32_t>(std::lround(target.width * scale));
    const auto height = static_cast<std::int32_t>(std::lround(target.height * scale));
    const std::int32_t x = (static_cast<std::int32_t>(present.extent.width) - width) / 2;
    const std::int32_t y = (static_cast<std::int32_t>(present.extent.height) - height) / 2;
    if (width != static_cast<std::int32_t>(present.extent.width) ||
        height != static_cast<std::int32_t>(present.extent.height)) {
      const VkClearColorValue clear{{background[0] / 255.0f, background[1] / 255.0f, background[2] / 255.0f, 1.0f}};
      const VkImageSubresourceRange range{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
      vkCmdClearColorImage(commands, present.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &clear, 1, &range);
      gpu::imageBarrier(commands, present.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                        VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_PIPELINE_STAGE_2_CLEAR_BIT,
                        VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_BLIT_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
    }
    VkImageBlit blit{};
    blit.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    blit.srcOffsets[1] = {static_cast<std::int32_t>(target.width), static_cast<std::int32_t>(target.height), 1};
    blit.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    blit.dstOffsets[0] = {x, y, 0};
    blit.dstOffsets[1] = {x + width, y + height, 1};
    vkCmdBlitImage(commands, colour, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, present.image,
                   VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &blit, VK_FILTER_NEAREST);
  }
  if (hook && present.decorated) {
    hook(commands, present);
    return;
  }
  // An XR runtime reads the image after the frame's submission on the same queue; its own
  // barrier waits for every earlier command, so none is named here.
  gpu::imageBarrier(commands, present.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, present.presented_layout,
                    VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_NONE,
                    VK_ACCESS_2_NONE);
}

}  // namespace

struct PointRenderer::Resources {
  Resources(const gpu::Device& d, gpu::MemoryAllocator& a, lod::NodeCache& n, const RendererOptions& o)
      : device(d),
        allocator(a),
        nodes(n),
        splat(d, kSplatCode, sizeof(shader::SplatPush), "splat"),
        splat_wide(d, kSplatWideCode, sizeof(shader::SplatPush), "splat, wide pass"),
        resolve(d, kResolveCode, sizeof(shader::ResolvePush), "resolve"),
        timeline(d),
        depth_out(d),
        ring(d, a, o.upload_ring_bytes),
        gpu_nodes(d, a, o.gpu_budget_bytes),
        surfels(o.background),
        slots{Slot{gpu::CommandPool(d, "frame slot 0"), {}, {}, {}},
              Slot{gpu::CommandPool(d, "frame slot 1"), {}, {}, {}}},
        readback_pool(d, "readback"),
        overlay_pass(d, a) {
    if (o.gpu_timing) {
      VkQueryPoolCreateInfo create{};
      create.sType = VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO;
      create.queryType = VK_QUERY_TYPE_TIMESTAMP;
      create.queryCount = kTimestamps * kFramesInFlight;
      gpu::check(vkCreateQueryPool(d.handle(), &create, nullptr, &timestamps), "vkCreateQueryPool");
    }
  }
  ~Resources() {
    if (timestamps != VK_NULL_HANDLE) vkDestroyQueryPool(device.handle(), timestamps, nullptr);
  }
  Resources(const Resources&) = delete;
  Resources& operator=(const Resources&) = delete;

  std::optional<IntensityRange> intensity_range;  // sampled at the first frame drawn by intensity

  // Before the splat, after it, after the resolve.
  static constexpr std::uint32_t kTimestamps = 3;

  void writeTimestamp(VkCommandBuffer commands, std::uint64_t value, std::uint32_t which) const {
    if (timestamps == VK_NULL_HANDLE) return;
    const auto query = static_cast<std::uint32_t>(value % kFramesInFlight) * kTimestamps + which;
    if (which == 0) vkCmdResetQueryPool(commands, timestamps, query, kTimestamps);
    vkCmdWriteTimestamp2(commands, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, timestamps, query);
  }

  struct Slot {
    gpu::CommandPool pool;
    gpu::Buffer chunks;  // host-visible SplatChunk table
    gpu::Buffer clip;    // host-visible ClipPlanes, made with the first clipped frame
    gpu::Buffer wide;    // the splat's list for its wide pass (WideSplatHeader, then blocks)
  };

  const gpu::Device& device;
  gpu::MemoryAllocator& allocator;
  lod::NodeCache& nodes;
  gpu::ComputePipeline splat;
  gpu::ComputePipeline splat_wide;
  gpu::ComputePipeline resolve;
  gpu::TimelineSemaphore timeline;
  std::uint64_t submitted = 0;  // the last value a submission signals
  gpu::DeletionQueue deletions;
  DepthOutPass depth_out;  // a headset eye's depth, when its image asks for it
  gpu::UploadRing ring;
  GpuNodeCache gpu_nodes;
  SurfelEstimates surfels;  // of streamed nodes, before their upload
  std::unique_ptr<RenderTarget> target;
  std::array<Slot, kFramesInFlight> slots;
  gpu::CommandPool readback_pool;
  gpu::Buffer readback;                         // host-visible
  std::shared_ptr<const SegmentLabels> labels;  // ColourMode::kSegment
  OverlayPass overlay_pass;
  std::shared_ptr<const OverlayScene> overlay;
  PresentHook present_hook;
  std::vector<ChunkOrigin> last_chunks;  // of the last rendered frame
  view::Camera last_camera;              // the last rendered frame's
  std::uint64_t frames = 0;
  std::uint64_t last_frame_value = 0;       // the timeline value of the last rendered frame
  VkQueryPool timestamps = VK_NULL_HANDLE;  // kTimestamps per frame slot, with gpu_timing

  void waitForAll() { timeline.wait(submitted, kNoTimeout); }

  void ensureTarget(std::uint32_t width, std::uint32_t height) {
    if (target && target->width == width && target->height == height) return;
    if (target) {
      std::shared_ptr<RenderTarget> old = std::move(target);  // the last frame may still use it
      deletions.defer(submitted, [old]() mutable { old.reset(); });
    }
    target = std::make_unique<RenderTarget>(device, allocator, width, height);
  }

  void ensureChunkCapacity(Slot& slot, std::size_t chunks) {
    const VkDeviceSize bytes = std::max<std::size_t>(chunks, 1) * sizeof(shader::SplatChunk);
    if (slot.chunks && slot.chunks.size() >= bytes) return;
    // The slot's last frame is done (paced): its table may go now.
    slot.chunks = gpu::Buffer(device, allocator, std::max<VkDeviceSize>(bytes, 2 * slot.chunks.size()),
                              VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, gpu::kHostMemory, "chunk table");
  }

  // Room for `blocks` in the slot's wide list; returns how many it has.
  std::uint32_t ensureWideCapacity(Slot& slot, std::uint64_t blocks) {
    const VkDeviceSize bytes = sizeof(shader::WideSplatHeader) + blocks * kWideBlockBytes;
    if (!slot.wide || slot.wide.size() < bytes) {
      // The slot's last frame is done (paced): its list may go now.
      slot.wide = gpu::Buffer(
          device, allocator, std::max<VkDeviceSize>(bytes, 2 * slot.wide.size()),
          VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
          gpu::kDeviceMemory, "wide splat list");
    }
    return static_cast<std::uint32_t>(
        std::min<VkDeviceSize>((slot.wide.size() - sizeof(shader::WideSplatHeader)) / kWideBlockBytes,
                               std::numeric_limits<std::uint32_t>::max()));
  }

  // The region's planes, relative to its anchor, into the slot's ClipPlanes; its address.
  VkDeviceAddress writeClip(Slot& slot, const view::ClipRegion& region) {
    if (!slot.clip) {
      slot.clip = gpu::Buffer(device, allocator, sizeof(shader::ClipPlanes), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                              gpu::kHostMemory, "clip planes");
    }
    shader::ClipPlanes planes{};
    const Eigen::Vector3d anchor = region.anchor();
    const view::ClipHalfSpaces clip = region.halfSpaces();
    std::vector<view::HalfSpace> spaces = clip.box_faces;
    planes.box_planes = static_cast<std::uint32_t>(spaces.size());
    planes.keep_outside_box = clip.keep_outside_box ? 1u : 0u;
    spaces.insert(spaces.end(), clip.planes.begin(), clip.planes.end());
    planes.plane_count = static_cast<std::uint32_t>(spaces.size());
    for (std::size_t i = 0; i < spaces.size(); ++i) {
      // n . (anchor + p) + d = n . p + (d + n . anchor)
      const view::HalfSpace& h = spaces[i];
      for (Eigen::Index a = 0; a < 3; ++a)
        planes.planes[4 * i + static_cast<std::size_t>(a)] = static_cast<float>(h[a]);
      planes.planes[4 * i + 3] = static_cast<float>(h[3] + h.head<3>().dot(anchor));
    }
    std::memcpy(slot.clip.mapped(), &planes, sizeof planes);
    return slot.clip.address();
  }

  void ensureReadback(VkDeviceSize bytes) {
    if (readback && readback.size() >= bytes) return;
    readback = gpu::Buffer(device, allocator, bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT, gpu::kHostMemory, "readback");
  }

  // Copies `regions` of `source` into the readback buffer, waiting for the GPU.
  void readBack(const gpu::Buffer& source, std::span<const VkBufferCopy> regions) {
    waitForAll();
    readback_pool.reset();
    VkCommandBuffer commands = readback_pool.begin();
    gpu::memoryBarrier(commands, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_COPY_BIT,
                       VK_ACCESS_2_SHADER_WRITE_BIT | VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_COPY_BIT,
                       VK_ACCESS_2_TRANSFER_READ_BIT);
    vkCmdCopyBuffer(commands, source.handle(), readback.handle(), static_cast<std::uint32_t>(regions.size()),
                    regions.data());
    gpu::memoryBarrier(commands, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                       VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT);
    gpu::submit(device, commands, timeline, ++submitted);
    waitForAll();
  }
};

PointRenderer::PointRenderer(const gpu::Device& device, gpu::MemoryAllocator& allocator, lod::NodeCache& nodes,
                             const RendererOptions& options)
    : resources_(std::make_unique<Resources>(device, allocator, nodes, options)) {}

PointRenderer::~PointRenderer() {
  try {
    resources_->waitForAll();
  } catch (const Error&) {
    // A lost device finishes nothing more; the destructors below release what is left.
  }
}

std::array<std::uint32_t, 2> PointRenderer::targetSize() const {
  const auto& target = resources_->target;
  return target ? std::array{target->width, target->height} : std::array<std::uint32_t, 2>{0, 0};
}

void PointRenderer::setOverlay(std::shared_ptr<const OverlayScene> overlay) {
  resources_->overlay = std::move(overlay);
}

void PointRenderer::setPresentHook(PresentHook hook) {
  resources_->present_hook = std::move(hook);
}

void PointRenderer::waitForFrames() {
  resources_->waitForAll();
}

void PointRenderer::setSegmentLabels(std::shared_ptr<const SegmentLabels> labels) {
  resources_->labels = std::move(labels);
}

GpuNodeCacheStats PointRenderer::gpuNodeStats() const {
  return resources_->gpu_nodes.stats();
}

FrameStats PointRenderer::render(const view::Camera& camera, const RenderSettings& settings, NodeLoading loading,
                                 std::span<const gpu::SwapchainImage> present_to, const view::Camera* choose_with) {
  Resources& r = *resources_;
  view::validateCamera(camera);
  if (settings.clip.active()) view::checkClipRegion(settings.clip, "render");
  const std::uint64_t value = ++r.submitted;
  // A frame that throws once it has its timeline value (a node that fails to load) must still
  // signal it, after the frames before it, or every later frame and readback would wait for it
  // forever.
  struct SignalIfUnsent {
    Resources& r;
    std::uint64_t value;
    bool sent = false;
    ~SignalIfUnsent() {
      if (sent) return;
      try {
        r.timeline.wait(value - 1, kNoTimeout);
        r.timeline.signalFromHost(value);
      } catch (...) {  // a destructor does not throw; the device is lost then anyway
      }
    }
  } unsent{r, value};
  FrameStats stats;
  stats.frame = ++r.frames;

  // 1. Pace.
  if (value > kFramesInFlight) r.timeline.wait(value - kFramesInFlight, kNoTimeout);
  const std::uint64_t completed = r.timeline.value();
  r.deletions.collect(completed);
  r.ring.reclaim(completed);
  Resources::Slot& slot = r.slots[value % kFramesInFlight];
  slot.pool.reset();
  r.ensureTarget(static_cast<std::uint32_t>(camera.viewport_width_px),
                 static_cast<std::uint32_t>(camera.viewport_height_px));
  const RenderTarget& target = *r.target;
  VkCommandBuffer commands = slot.pool.begin();
  // The previous frame (its resolve, overlays and copies) used what this frame overwrites.
  gpu::memoryBarrier(
      commands,
      VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT | VK_PIPELINE_STAGE_2_COPY_BIT,
      VK_ACCESS_2_SHADER_READ_BIT | VK_ACCESS_2_SHADER_WRITE_BIT | VK_ACCESS_2_TRANSFER_READ_BIT |
          VK_ACCESS_2_TRANSFER_WRITE_BIT,
      VK_PIPELINE_STAGE_2_CLEAR_BIT | VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
      VK_ACCESS_2_TRANSFER_WRITE_BIT | VK_ACCESS_2_SHADER_WRITE_BIT);

  // 2. Select and upload.
  const lod::Octree& octree = r.nodes.octree();
  if (choose_with != nullptr) view::validateCamera(*choose_with);
  const NodeSelection selection =
      selectNodes(octree, choose_with != nullptr ? *choose_with : camera, settings.selection, settings.clip);
  stats.nodes_selected = selection.nodes.size();
  stats.points_selected = selection.points;
  stats.budget_reached = selection.budget_reached;
  const ColourMode mode = effectiveColourMode(settings.colour, octree.header().attributes);
  if (mode == ColourMode::kIntensity && !r.intensity_range) r.intensity_range = sampleIntensityRange(r.nodes);
  const IntensityRange intensity = r.intensity_range.value_or(IntensityRange{});
  const SegmentLabels* labels = mode == ColourMode::kSegment ? r.labels.get() : nullptr;
  struct Drawn {
    const lod::NodeInfo* info;
    const GpuNode* node;
    VkDeviceAddress labels;  // 0: none
  };
  std::vector<Drawn> drawn;
  drawn.reserve(selection.nodes.size());
  for (std::size_t n = 0; n < selection.nodes.size(); ++n) {
    const lod::NodeInfo* info = selection.nodes[n];
    // A node without points (a COPC inner node whose children hold them all) is selected so
    // that its children are, and has nothing to draw.
    if (info->point_count == 0) continue;
    const GpuNode* node = r.gpu_nodes.use(info->key, value);
    if (node == nullptr) {
      const std::shared_ptr<const lod::NodePoints> points =
          loading == NodeLoading::kWait ? r.nodes.get(info->key) : r.nodes.tryGet(info->key);
      if (points) {
        // Headless renders wait for the surfels; a streaming frame uploads the node once they
        // are ready.
        const double cell_size = octree.cube().cellSize(info->key.level);
        // A streaming frame waits for the ancestors' points too (the parent stands in meanwhile).
        const std::optional<NodeAncestors> ancestors = nodeAncestors(r.nodes, info->key, loading == NodeLoading::kWait);
        std::shared_ptr<const std::vector<Surfel>> surfels;
        if (ancestors && loading == NodeLoading::kWait) {
          surfels = std::make_shared<const std::vector<Surfel>>(nodeSurfels(*points, *ancestors, cell_size));
        } else if (ancestors) {
          surfels = r.surfels.find(points, *ancestors, cell_size);
        }
        if (surfels) node = r.gpu_nodes.upload(*points, *surfels, cell_size, commands, r.ring, value);
        if (node != nullptr) {
          stats.bytes_uploaded += node->points.size();
          r.surfels.forget(info->key);
        }
      }
    }
    if (node == nullptr) {
      ++stats.nodes_missing;
      continue;
    }
    VkDeviceAddress label_address = 0;
    if (labels != nullptr) {
      const auto found = labels->nodes.find(info->key);
      const gpu::Buffer* buffer =
          found == labels->nodes.end()
              ? nullptr
              : r.gpu_nodes.labels(info->key, found->second, labels->version, commands, r.ring, value, r.deletions);
      if (buffer != nullptr) label_address = buffer->address();
    }
    drawn.push_back({info, node, label_address});
  }
  r.ring.close(value);

  // 3. The chunk table.
  std::size_t chunk_count = 0;
  for (const Drawn& d : drawn) chunk_count += (d.node->point_count + shader::kChunkPoints - 1) / shader::kChunkPoints;
  r.ensureChunkCapacity(slot, chunk_count);
  auto* chunks = static_cast<shader::SplatChunk*>(slot.chunks.mapped());
  r.last_chunks.clear();
  r.last_chunks.reserve(chunk_count);

  const double elevation_base = octree.header().bounds.min[2];
  const Eigen::Vector3d clip_anchor = settings.clip.anchor();
  // Each point a disc of the drawn cloud's spacing around it (surfels.h, splat_spacing.h).
  std::vector<DrawnNode> drawn_nodes;
  drawn_nodes.reserve(drawn.size());
  for (const Drawn& d : drawn) drawn_nodes.push_back({d.info->key, d.node->point_count, d.node->octant_points});
  const std::vector<std::array<float, 8>> scales = octantRadiusScales(drawn_nodes);
  std::size_t c = 0;
  // Whether a node's discs may reach a pixel's radius (the shader's kMinDiscPx): its largest
  // at its cell's nearest corner (the view depth is linear, least at a corner).
  const double pixels_per_metre = 1.0 / view::metresPerPixel(camera, 1.0);
  const Eigen::Vector3d forward = view::viewDirection(camera);
  const auto castsDiscs = [&](const Drawn& d, float max_scale) {
    const lod::Box3 cell = octree.cube().cellBox(d.info->key);
    double nearest = std::numeric_limits<double>::infinity();
    for (int corner = 0; corner < 8; ++corner) {
      const Eigen::Vector3d p(cell.min[0] + (corner & 1 ? cell.max[0] - cell.min[0] : 0.0),
                              cell.min[1] + (corner & 2 ? cell.max[1] - cell.min[1] : 0.0),
                              cell.min[2] + (corner & 4 ? cell.max[2] - cell.min[2] : 0.0));
      nearest = std::min(nearest, forward.dot(p - camera.position));
    }
    if (camera.projection != view::Projection::kPerspective) nearest = 1.0;
    return nearest <= camera.near_m || d.node->max_radius_m * max_scale * pixels_per_metre / nearest >= 1.0;
  };
  for (std::size_t n = 0; n < drawn.size(); ++n) {
    const Drawn& d = drawn[n];
    const auto half_cell_m = static_cast<float>(0.5 * octree.cube().cellSize(d.info->key.level));
    const std::uint32_t discs = castsDiscs(d, *std::max_element(scales[n].begin(), scales[n].end())) ? 1u : 0u;
    const std::array<double, 3> origin = octree.cube().cellMin(d.info->key);
    const SplatTransform transform = splatTransform(camera, origin);
    for (std::uint32_t first = 0; first < d.node->point_count; first += shader::kChunkPoints) {
      shader::SplatChunk& chunk = chunks[c++];
      std::memcpy(chunk.clip_from_node, transform.clip_from_origin.data(), sizeof chunk.clip_from_node);
      std::memcpy(chunk.depth_from_node, transform.depth_from_origin.data(), sizeof chunk.depth_from_node);
      chunk.points = d.node->points.address() + VkDeviceAddress{first} * sizeof(lod::PackedPoint);
      chunk.labels = d.labels == 0 ? 0 : d.labels + VkDeviceAddress{first} * sizeof(std::uint32_t);
      chunk.scans = d.node->scans_offset == 0 ? 0
                                              : d.node->points.address() + d.node->scans_offset +
                                                    VkDeviceAddress{first} * sizeof(std::uint16_t);
      chunk.point_count = std::min(shader::kChunkPoints, d.node->point_count - first);
      chunk.elevation_offset = static_cast<float>(origin[2] - elevation_base);
      chunk.surfels = d.node->points.address() + d.node->surfels_offset + VkDeviceAddress{first} * sizeof(Surfel);
      std::copy(scales[n].begin(), scales[n].end(), chunk.octant_scale);
      chunk.half_cell_m = half_cell_m;
      chunk.discs = discs;
      for (std::size_t a = 0; a < 3; ++a) {
        chunk.clip_offset[a] = static_cast<float>(origin[a] - clip_anchor[static_cast<Eigen::Index>(a)]);
      }
      r.last_chunks.push_back({d.info->key, first});
    }
    ++stats.nodes_drawn;
    stats.points_drawn += d.node->point_count;
  }
  assert(chunk_count < (std::size_t{1} << (32 - shader::kChunkBits)) && "more chunks than ids: lower the point budget");

  // 4. Record and submit.
  // The wide list has a block for every eighth point drawn, and more for small frames: a block
  // needs a footprint of more than a thousand pixels, so that 2 M points fill it with discs
  // covering the screen 270 times over (1280 x 720), beyond any use; the splat then covers the
  // rest itself, cut short on lavapipe alone. 1 MB per million points, per frame in flight.
  const std::uint32_t wide_capacity =
      r.ensureWideCapacity(slot, std::max<std::uint64_t>(stats.points_drawn / 8, 65536));
  vkCmdFillBuffer(commands, target.visibility.handle(), 0, VK_WHOLE_SIZE, 0xFFFFFFFFu);
  const shader::WideSplatHeader empty_list{{0, 0, 1}, 0, 0, 0};
  vkCmdUpdateBuffer(commands, slot.wide.handle(), 0, sizeof empty_list, &empty_list);
  gpu::memoryBarrier(commands, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                     VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                     VK_ACCESS_2_SHADER_READ_BIT | VK_ACCESS_2_SHADER_WRITE_BIT);
  const auto count = static_cast<std::uint32_t>(chunk_count);
  r.writeTimestamp(commands, value, 0);
  if (count > 0) {
    const shader::SplatPush push{slot.chunks.address(),
                                 target.visibility.address(),
                                 target.width,
                                 target.height,
                                 count,
                                 static_cast<float>(camera.near_m),
                                 settings.clip.active() ? r.writeClip(slot, settings.clip) : 0,
                                 static_cast<float>(pixels_per_metre),
                                 camera.projection == view::Projection::kPerspective ? 1u : 0u,
                                 shaderSplatShape(settings.splat),
                                 0u,
                                 slot.wide.address(),
                                 wide_capacity,
                                 0u};
    r.splat.dispatch(commands, push, count);
    gpu::memoryBarrier(
        commands, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_WRITE_BIT,
        VK_PIPELINE_STAGE_2_DRAW_INDIRECT_BIT | VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
        VK_ACCESS_2_INDIRECT_COMMAND_READ_BIT | VK_ACCESS_2_SHADER_READ_BIT | VK_ACCESS_2_SHADER_WRITE_BIT);
    r.splat_wide.dispatchIndirect(commands, push, slot.wide.handle(), 0);
    gpu::memoryBarrier(commands, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_WRITE_BIT,
                       VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_READ_BIT);
  }
  const shader::ResolvePush resolve{slot.chunks.address(),
                                    target.visibility.address(),
                                    target.resolved.address(),
                                    target.colour.address(),
                                    target.width,
                                    target.height,
                                    count,
                                    shaderColourMode(mode),
                                    0.0f,
                                    static_cast<float>(octree.header().bounds.max[2] - elevation_base),
                                    intensity.min,
                                    intensity.max,
                                    settings.edl ? settings.edl_strength : 0.0f,
                                    packRgba(settings.background)};
  const std::uint32_t group = shader::kResolveGroupSize;
  r.writeTimestamp(commands, value, 1);
  r.resolve.dispatch(commands, resolve, (target.width + group - 1) / group, (target.height + group - 1) / group);
  r.writeTimestamp(commands, value, 2);
  const bool overlaid = r.overlay && !r.overlay->empty() &&
                        r.overlay_pass.record(commands, value % kFramesInFlight, target, *r.overlay, camera,
                                              settings.overlay_depth_tolerance);
  const gpu::SwapchainImage* window = nullptr;  // the one image with semaphores, if any
  bool colour_image_ready = overlaid;
  for (const gpu::SwapchainImage& image : present_to) {
    recordPresentation(commands, target, image, colour_image_ready, settings.background, r.present_hook);
    colour_image_ready = true;
    if (image.depth != VK_NULL_HANDLE) {
      r.depth_out.record(commands, target, camera, image.depth, image.depth_format,
                         VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL, r.deletions, value);
    }
    if (image.acquired != VK_NULL_HANDLE || image.rendered != VK_NULL_HANDLE) {
      assert(window == nullptr && "a frame presents to at most one image with semaphores");
      window = &image;
    }
  }
  if (window != nullptr) {
    // The hook may draw into the image too: its colour output waits for the acquire as well.
    gpu::submit(r.device, commands, r.timeline, value, window->acquired,
                VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT | VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                window->rendered);
  } else {
    gpu::submit(r.device, commands, r.timeline, value);
  }
  unsent.sent = true;
  r.last_frame_value = value;
  r.last_camera = camera;

  // 5. Evict.
  r.gpu_nodes.evict(value, r.deletions);
  return stats;
}

FrameStats PointRenderer::renderComplete(const view::Camera& camera, const RenderSettings& settings) {
  // Each frame uploads what the ring holds; a frame that uploads nothing cannot do better later.
  FrameStats stats = render(camera, settings, NodeLoading::kWait);
  while (!stats.complete()) {
    const FrameStats next = render(camera, settings, NodeLoading::kWait);
    if (next.bytes_uploaded == 0 && resources_->ring.bytesInFlight() == 0) {
      throw Error("the renderer cannot upload the " + std::to_string(next.nodes_missing) +
                  " nodes left: raise the upload ring above the largest node");
    }
    stats = next;
  }
  return stats;
}

std::optional<GpuTimings> PointRenderer::gpuTimings() {
  Resources& r = *resources_;
  if (r.timestamps == VK_NULL_HANDLE || r.last_frame_value == 0) return std::nullopt;
  r.waitForAll();
  std::array<std::uint64_t, Resources::kTimestamps> ticks{};
  const auto first = static_cast<std::uint32_t>(r.last_frame_value % kFramesInFlight) * Resources::kTimestamps;
  gpu::check(vkGetQueryPoolResults(r.device.handle(), r.timestamps, first, Resources::kTimestamps, sizeof ticks,
                                   ticks.data(), sizeof(std::uint64_t), VK_QUERY_RESULT_64_BIT),
             "vkGetQueryPoolResults");
  const double ms_per_tick = r.device.properties().limits.timestampPeriod * 1e-6;
  return GpuTimings{static_cast<double>(ticks[1] - ticks[0]) * ms_per_tick,
                    static_cast<double>(ticks[2] - ticks[1]) * ms_per_tick};
}

io::RgbaImage PointRenderer::readColour() {
  Resources& r = *resources_;
  if (!r.target) return {};
  const RenderTarget& target = *r.target;
  r.ensureReadback(target.colour.size());
  const VkBufferCopy all{0, 0, target.colour.size()};
  r.readBack(target.colour, std::span(&all, 1));
  io::RgbaImage image{static_cast<int>(target.width), static_cast<int>(target.height), {}};
  const auto* bytes = static_cast<const std::uint8_t*>(r.readback.mapped());
  image.rgba.assign(bytes, bytes + target.colour.size());
  return image;
}

// What counts as the front surface when picking: within this fraction of the nearest depth in
// the window plus this many metres (scanner noise, a surface seen at a grazing angle).
constexpr float kPickFrontFraction = 0.02f;
constexpr float kPickFrontMetres = 0.02f;

std::optional<PickedPoint> PointRenderer::pick(int x, int y, int radius_px) {
  Resources& r = *resources_;
  if (!r.target || r.last_chunks.empty()) return std::nullopt;
  const RenderTarget& target = *r.target;
  const int x0 = std::max(x - radius_px, 0), x1 = std::min(x + radius_px, static_cast<int>(target.width) - 1);
  const int y0 = std::max(y - radius_px, 0), y1 = std::min(y + radius_px, static_cast<int>(target.height) - 1);
  if (x0 > x1 || y0 > y1) return std::nullopt;
  const auto columns = static_cast<VkDeviceSize>(x1 - x0 + 1);
  std::vector<VkBufferCopy> rows;
  for (int row = y0; row <= y1; ++row) {
    rows.push_back({(static_cast<VkDeviceSize>(row) * target.width + static_cast<VkDeviceSize>(x0)) * 8,
                    static_cast<VkDeviceSize>(row - y0) * columns * 8, columns * 8});
  }
  r.ensureReadback(rows.size() * columns * 8);
  r.readBack(target.resolved, rows);

  const auto* values = static_cast<const std::uint64_t*>(r.readback.mapped());
  const auto depthOf = [](std::uint64_t v) {
    const auto bits = static_cast<std::uint32_t>(v >> 32);
    float depth = 0.0f;
    std::memcpy(&depth, &bits, sizeof depth);
    return depth;
  };
  // The front surface: a scan sees both faces of a wall, and through the gaps of a sparse near
  // face the far one shows. Only points near the nearest depth in the window count.
  float nearest_depth = INFINITY;
  for (int row = y0; row <= y1; ++row) {
    for (int column = x0; column <= x1; ++column) {
      const std::uint64_t v =
          values[static_cast<std::size_t>(row - y0) * columns + static_cast<std::size_t>(column - x0)];
      const long distance = long{column - x} * (column - x) + long{row - y} * (row - y);
      if (v != ~std::uint64_t{0} && distance <= long{radius_px} * radius_px) {
        nearest_depth = std::min(nearest_depth, depthOf(v));
      }
    }
  }
  const float front_depth = nearest_depth * (1.0f + kPickFrontFraction) + kPickFrontMetres;
  // The front pixel nearest the cursor (the nearer point on a tie), and the nodes whose points
  // the window's front pixels show.
  std::optional<std::uint64_t> hit;
  int hit_column = 0, hit_row = 0;
  long hit_distance = 0;
  std::vector<lod::CellKey> shown_nodes;
  for (int row = y0; row <= y1; ++row) {
    for (int column = x0; column <= x1; ++column) {
      const std::uint64_t v =
          values[static_cast<std::size_t>(row - y0) * columns + static_cast<std::size_t>(column - x0)];
      if (v == ~std::uint64_t{0} || depthOf(v) > front_depth) continue;
      const long distance = long{column - x} * (column - x) + long{row - y} * (row - y);
      if (distance > long{radius_px} * radius_px) continue;
      const lod::CellKey& node = r.last_chunks.at(static_cast<std::uint32_t>(v) >> shader::kChunkBits).node;
      if (std::find(shown_nodes.begin(), shown_nodes.end(), node) == shown_nodes.end()) shown_nodes.push_back(node);
      if (hit && (distance > hit_distance || (distance == hit_distance && v >= *hit))) continue;
      hit = v;
      hit_column = column;
      hit_row = row;
      hit_distance = distance;
    }
  }
  if (!hit) return std::nullopt;
  // The surface there: the pixel's centre at the depth the splat kept, a disc's plane's. Up close
  // a point's disc covers many pixels, and which of the overlapping discs wins one is a matter of
  // depths within the noise (or of ids): the point meant is the one nearest that surface point,
  // among the points of the nodes the window shows.
  const view::Ray ray = view::rayThroughPixel(r.last_camera, hit_column + 0.5, hit_row + 0.5);
  const Eigen::Vector3d forward = view::viewDirection(r.last_camera);
  const Eigen::Vector3d surface = ray.origin + ray.direction * (depthOf(*hit) / ray.direction.dot(forward));
  PickedPoint best;
  double best_distance2 = INFINITY;
  const auto search = [&](const lod::CellKey& node) {
    const std::shared_ptr<const lod::NodePoints> points = r.nodes.get(node);
    for (std::size_t i = 0; i < points->size(); ++i) {
      const std::array<double, 3> p = points->position(i);
      const double distance2 = (Eigen::Vector3d(p[0], p[1], p[2]) - surface).squaredNorm();
      if (distance2 >= best_distance2) continue;
      best_distance2 = distance2;
      best.position = p;
      best.node = node;
      best.index = static_cast<std::uint32_t>(i);
    }
  };
  for (const lod::CellKey& node : shown_nodes) search(node);
  // A nearer point may be another drawn node's, whose discs won no pixel of the window.
  const lod::Cube& cube = r.nodes.octree().cube();
  const std::array<double, 3> at{surface.x(), surface.y(), surface.z()};
  for (std::size_t c = 0; c < r.last_chunks.size(); ++c) {
    const lod::CellKey& node = r.last_chunks[c].node;
    if (c > 0 && r.last_chunks[c - 1].node == node) continue;  // a node's chunks are consecutive
    if (cube.squaredDistance(node, at) >= best_distance2) continue;
    if (std::find(shown_nodes.begin(), shown_nodes.end(), node) == shown_nodes.end()) search(node);
  }
  const Eigen::Vector3d world(best.position[0], best.position[1], best.position[2]);
  best.depth_m = static_cast<float>(forward.dot(world - r.last_camera.position));
  // Its own pixel where that lies in the window, else the pixel it was found from.
  const std::optional<Eigen::Vector2d> own = view::pixelOf(r.last_camera, world);
  const bool own_in_window = own && (own->array().floor().matrix() - Eigen::Vector2d(x, y)).squaredNorm() <=
                                        static_cast<double>(radius_px) * radius_px;
  best.pixel_x = own_in_window ? static_cast<int>(std::floor(own->x())) : hit_column;
  best.pixel_y = own_in_window ? static_cast<int>(std::floor(own->y())) : hit_row;
  return best;
}

}  // namespace plumb::render
