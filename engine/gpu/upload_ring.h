#pragma once
// A ring of host-visible memory that data goes through on its way to device-local buffers. A
// frame takes spans from the ring, records copies out of them into its command buffer, and
// closes its spans with its timeline value; once the GPU passes that value, reclaim() makes the
// space free again. A span that does not fit waits for a later frame (allocate returns nothing):
// the ring never blocks and never grows. Not thread-safe: the render thread owns it.

#include <vulkan/vulkan.h>

#include <cstddef>
#include <cstdint>
#include <deque>
#include <optional>

#include "engine/gpu/buffer.h"

namespace plumb::gpu {

struct UploadSpan {
  VkDeviceSize offset;  // in buffer()
  std::byte* data;      // where the host writes the bytes
};

class UploadRing {
 public:
  UploadRing(const Device& device, MemoryAllocator& allocator, VkDeviceSize capacity);

  // `bytes` (> 0) at an offset aligned to `alignment` (a power of two), or nothing while frames
  // in flight hold too much of the ring (or `bytes` exceeds the capacity).
  std::optional<UploadSpan> allocate(VkDeviceSize bytes, VkDeviceSize alignment = 16);
  // The spans allocated since the last close belong to the submission that signals `value`.
  void close(std::uint64_t value);
  // Frees the spans of submissions whose value is at most `completed`.
  void reclaim(std::uint64_t completed);

  VkBuffer buffer() const { return buffer_.handle(); }
  VkDeviceSize capacity() const { return buffer_.size(); }
  VkDeviceSize bytesInFlight() const;

 private:
  struct Closed {
    VkDeviceSize end;  // the ring position after the submission's last span
    std::uint64_t value;
  };

  Buffer buffer_;
  // Live bytes run from tail_ to head_, wrapping at the capacity; head_ == tail_ is empty or full.
  VkDeviceSize head_ = 0, tail_ = 0;
  bool empty_ = true;
  bool open_ = false;  // spans allocated since the last close
  std::deque<Closed> closed_;
};

}  // namespace plumb::gpu
