#include "engine/gpu/upload_ring.h"

#include <cassert>

namespace plumb::gpu {

UploadRing::UploadRing(const Device& device, MemoryAllocator& allocator, VkDeviceSize capacity)
    : buffer_(device, allocator, capacity, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, kHostMemory, "upload ring") {}

std::optional<UploadSpan> UploadRing::allocate(VkDeviceSize bytes, VkDeviceSize alignment) {
  assert(bytes > 0 && (alignment & (alignment - 1)) == 0 && "a span of no bytes or an alignment not a power of two");
  const VkDeviceSize capacity = buffer_.size();
  if (empty_) head_ = tail_ = 0;
  const VkDeviceSize aligned = (head_ + alignment - 1) & ~(alignment - 1);
  VkDeviceSize offset = 0;
  if (empty_ || head_ > tail_) {
    // Free: [head_, capacity) and [0, tail_). The bytes skipped at the end on a wrap stay with
    // this submission and come back with it.
    if (aligned + bytes <= capacity) {
      offset = aligned;
    } else if (bytes <= tail_ || (empty_ && bytes <= capacity)) {
      offset = 0;
    } else {
      return std::nullopt;
    }
  } else if (head_ < tail_ && aligned + bytes <= tail_) {
    offset = aligned;  // free: [head_, tail_)
  } else {
    return std::nullopt;  // full, or the gap is too small
  }
  head_ = offset + bytes;
  empty_ = false;
  open_ = true;
  return UploadSpan{offset, static_cast<std::byte*>(buffer_.mapped()) + offset};
}

void UploadRing::close(std::uint64_t value) {
  if (!open_) return;
  assert((closed_.empty() || closed_.back().value <= value) && "timeline values go forward");
  closed_.push_back({head_, value});
  open_ = false;
}

void UploadRing::reclaim(std::uint64_t completed) {
  while (!closed_.empty() && closed_.front().value <= completed) {
    tail_ = closed_.front().end;
    closed_.pop_front();
  }
  if (closed_.empty() && !open_) empty_ = true;
}

VkDeviceSize UploadRing::bytesInFlight() const {
  if (empty_) return 0;
  if (head_ > tail_) return head_ - tail_;
  return buffer_.size() - tail_ + head_;  // wrapped, or full when equal
}

}  // namespace plumb::gpu
