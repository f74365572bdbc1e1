#include "engine/render/gpu_node_cache.h"

#include <algorithm>
#include <cassert>
#include <cstring>
#include <memory>
#include <string>
#include <utility>

#include "engine/gpu/deletion_queue.h"
#include "engine/gpu/upload_ring.h"
#include "engine/lod/octree.h"
#include "engine/render/splat_spacing.h"

namespace plumb::render {

GpuNodeCache::GpuNodeCache(const gpu::Device& device, gpu::MemoryAllocator& allocator, std::uint64_t budget_bytes)
    : device_(device), allocator_(allocator), budget_bytes_(budget_bytes) {}

void GpuNodeCache::touch(Entry& entry, std::uint64_t frame) {
  entry.node.last_frame = frame;
  recency_.splice(recency_.begin(), recency_, entry.recency);
}

const GpuNode* GpuNodeCache::use(const lod::CellKey& key, std::uint64_t frame) {
  const auto found = entries_.find(key);
  if (found == entries_.end()) return nullptr;
  touch(found->second, frame);
  return &found->second.node;
}

const GpuNode* GpuNodeCache::upload(const lod::NodePoints& points, std::span<const Surfel> surfels, double cell_size,
                                    VkCommandBuffer commands, gpu::UploadRing& ring, std::uint64_t frame) {
  if (points.points.empty()) return nullptr;  // the renderer skips empty nodes (COPC has some)
  assert((points.scans.empty() || points.scans.size() == points.points.size()) && "a scan index per point, or none");
  assert(surfels.size() == points.points.size() && "a surfel per point");
  const VkDeviceSize point_bytes = points.points.size() * sizeof(lod::PackedPoint);
  const VkDeviceSize scan_bytes = points.scans.size() * sizeof(std::uint16_t);
  const VkDeviceSize surfels_offset = (point_bytes + scan_bytes + 7) / 8 * 8;  // surfels are 8-byte aligned
  const VkDeviceSize bytes = surfels_offset + points.points.size() * sizeof(Surfel);
  const std::optional<gpu::UploadSpan> span = ring.allocate(bytes);
  if (!span) return nullptr;
  std::memcpy(span->data, points.points.data(), point_bytes);
  if (!points.scans.empty()) std::memcpy(span->data + point_bytes, points.scans.data(), scan_bytes);
  std::memcpy(span->data + surfels_offset, surfels.data(), surfels.size() * sizeof(Surfel));

  const std::string name = "node " + std::to_string(points.key.level) + "/" + std::to_string(points.key.x) + "/" +
                           std::to_string(points.key.y) + "/" + std::to_string(points.key.z);
  GpuNode node;
  node.points =
      gpu::Buffer(device_, allocator_, bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                  gpu::kDeviceMemory, name.c_str());
  node.point_count = static_cast<std::uint32_t>(points.points.size());
  node.surfels_offset = surfels_offset;
  for (const Surfel& surfel : surfels) node.max_radius_m = std::max(node.max_radius_m, surfel.radius_m);
  node.octant_points = countOctants(points.points, static_cast<float>(0.5 * cell_size));
  node.scans_offset = points.scans.empty() ? 0 : point_bytes;
  const VkBufferCopy copy{span->offset, 0, bytes};
  vkCmdCopyBuffer(commands, ring.buffer(), node.points.handle(), 1, &copy);

  recency_.push_front(points.key);
  Entry& entry = entries_.insert_or_assign(points.key, Entry{std::move(node), recency_.begin()}).first->second;
  entry.node.last_frame = frame;
  stats_.bytes += bytes;
  ++stats_.nodes;
  ++stats_.uploads;
  return &entry.node;
}

const gpu::Buffer* GpuNodeCache::labels(const lod::CellKey& key, const std::vector<std::uint32_t>& labels,
                                        std::uint64_t version, VkCommandBuffer commands, gpu::UploadRing& ring,
                                        std::uint64_t frame, gpu::DeletionQueue& deletions) {
  GpuNode& node = entries_.at(key).node;
  assert(labels.size() == node.point_count && "segment labels for another number of points than the node has");
  if (node.labels && node.labels_version == version) return &node.labels;
  const VkDeviceSize bytes = labels.size() * sizeof(std::uint32_t);
  const std::optional<gpu::UploadSpan> span = ring.allocate(bytes);
  if (!span) return nullptr;
  std::memcpy(span->data, labels.data(), bytes);
  if (node.labels) {
    auto old = std::make_shared<gpu::Buffer>(std::move(node.labels));
    stats_.bytes -= old->size();
    deletions.defer(frame, [old]() mutable { old.reset(); });
  }
  node.labels =
      gpu::Buffer(device_, allocator_, bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                  gpu::kDeviceMemory, "segment labels");
  node.labels_version = version;
  const VkBufferCopy copy{span->offset, 0, bytes};
  vkCmdCopyBuffer(commands, ring.buffer(), node.labels.handle(), 1, &copy);
  stats_.bytes += bytes;
  return &node.labels;
}

void GpuNodeCache::evict(std::uint64_t frame, gpu::DeletionQueue& deletions) {
  while (stats_.bytes > budget_bytes_ && !recency_.empty()) {
    const lod::CellKey key = recency_.back();
    const auto found = entries_.find(key);
    if (found->second.node.last_frame >= frame) break;  // everything left is drawn by this frame
    GpuNode& node = found->second.node;
    stats_.bytes -= node.points.size() + (node.labels ? node.labels.size() : 0);
    --stats_.nodes;
    ++stats_.evictions;
    auto buffers =
        std::make_shared<std::pair<gpu::Buffer, gpu::Buffer>>(std::move(node.points), std::move(node.labels));
    deletions.defer(frame, [buffers]() mutable { buffers.reset(); });
    entries_.erase(found);
    recency_.pop_back();
  }
}

}  // namespace plumb::render
