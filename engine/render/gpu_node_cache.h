#pragma once
// The octree nodes resident on the GPU: one device-local buffer of lod::PackedPoint per node
// (followed by the points' 16-bit scan indices where the cloud has them),
// filled through the upload ring, evicted least-recently-used beyond a byte budget. Evicted
// buffers go through the deletion queue, so a frame in flight keeps what it draws. Nodes in use
// by the current frame are never evicted (the point budget bounds them). Not thread-safe: the
// render thread owns it.

#include <vulkan/vulkan.h>

#include <array>
#include <cstdint>
#include <list>
#include <span>
#include <unordered_map>

#include "engine/gpu/buffer.h"
#include "engine/lod/cell_key.h"
#include "engine/render/surfels.h"

namespace plumb::gpu {
class DeletionQueue;
class UploadRing;
}  // namespace plumb::gpu
namespace plumb::lod {
struct NodePoints;
}

namespace plumb::render {

struct GpuNode {
  gpu::Buffer points;
  std::uint32_t point_count = 0;
  std::array<std::uint32_t, 8> octant_points{};  // splat_spacing.h's countOctants
  VkDeviceSize scans_offset = 0;                 // where the scan indices start in `points`; 0: none
  VkDeviceSize surfels_offset = 0;               // where the surfels (surfels.h) start in `points`
  float max_radius_m = 0.0f;                     // of its surfels
  std::uint64_t last_frame = 0;                  // the last frame that drew it
  gpu::Buffer labels;                            // uint32 per point (segment colours), when uploaded
  std::uint64_t labels_version = 0;
};

struct GpuNodeCacheStats {
  std::uint64_t nodes = 0;
  std::uint64_t bytes = 0;
  std::uint64_t uploads = 0;    // since the cache was made
  std::uint64_t evictions = 0;  // since the cache was made
};

class GpuNodeCache {
 public:
  GpuNodeCache(const gpu::Device& device, gpu::MemoryAllocator& allocator, std::uint64_t budget_bytes);

  // The resident node of `key`, marked as drawn by `frame`; null when it is not resident.
  const GpuNode* use(const lod::CellKey& key, std::uint64_t frame);

  // Records the upload of `points` and their `surfels` into `commands` (a copy out of the ring;
  // the caller puts a barrier before the first read) and returns the new resident node, marked
  // as drawn by `frame`. Null when the ring has no room this frame: try again in a later one.
  // `cell_size`: the node's size, where its octants split (GpuNode::octant_points).
  const GpuNode* upload(const lod::NodePoints& points, std::span<const Surfel> surfels, double cell_size,
                        VkCommandBuffer commands, gpu::UploadRing& ring, std::uint64_t frame);

  // The node's segment labels of `version` on the GPU, uploading them (recorded into `commands`)
  // when the node holds another version; null when the ring has no room this frame. The node
  // must be resident; `labels` must have one entry per point. A replaced labels buffer is
  // destroyed once the GPU passes `frame`.
  const gpu::Buffer* labels(const lod::CellKey& key, const std::vector<std::uint32_t>& labels, std::uint64_t version,
                            VkCommandBuffer commands, gpu::UploadRing& ring, std::uint64_t frame,
                            gpu::DeletionQueue& deletions);

  // Evicts least recently drawn nodes, none drawn by `frame`, until the budget holds; each
  // buffer is destroyed once the GPU passes `frame`.
  void evict(std::uint64_t frame, gpu::DeletionQueue& deletions);

  GpuNodeCacheStats stats() const { return stats_; }

 private:
  struct Entry {
    GpuNode node;
    std::list<lod::CellKey>::iterator recency;
  };
  void touch(Entry& entry, std::uint64_t frame);

  const gpu::Device& device_;
  gpu::MemoryAllocator& allocator_;
  std::uint64_t budget_bytes_;
  std::list<lod::CellKey> recency_;  // most recently drawn first
  std::unordered_map<lod::CellKey, Entry, lod::CellKeyHash> entries_;
  GpuNodeCacheStats stats_;
};

}  // namespace plumb::render
