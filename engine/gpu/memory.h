#pragma once
// Device memory for buffers, in blocks (Debian has no VMA). Vulkan allows only a few thousand
// allocations and each is slow, so memory comes in blocks of `block_size` per memory type, cut
// into aligned ranges by a first-fit free list whose neighbours merge when freed. A request
// larger than a block gets a block of its own. Host-visible blocks stay mapped. An empty block
// is kept for the next request of its type, a second one is freed.
//
// Buffers only: images would also need bufferImageGranularity between linear and optimal
// resources, which this does not track. Thread-safe.

#include <vulkan/vulkan.h>

#include <cstddef>
#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <vector>

namespace plumb::gpu {

class Device;
class MemoryAllocator;

// A range of device memory, freed when the handle goes (move-only).
class Allocation {
 public:
  Allocation() = default;
  ~Allocation();
  Allocation(Allocation&& other) noexcept;
  Allocation& operator=(Allocation&& other) noexcept;
  Allocation(const Allocation&) = delete;
  Allocation& operator=(const Allocation&) = delete;

  VkDeviceMemory memory() const { return memory_; }
  VkDeviceSize offset() const { return offset_; }
  VkDeviceSize size() const { return size_; }
  // The range's first byte in host memory; null unless the memory is host-visible.
  void* mapped() const { return mapped_; }
  explicit operator bool() const { return owner_ != nullptr; }

 private:
  friend class MemoryAllocator;
  MemoryAllocator* owner_ = nullptr;
  std::size_t block_ = 0;
  VkDeviceMemory memory_ = VK_NULL_HANDLE;
  VkDeviceSize offset_ = 0, size_ = 0;
  void* mapped_ = nullptr;
};

class MemoryAllocator {
 public:
  explicit MemoryAllocator(const Device& device, VkDeviceSize block_size = VkDeviceSize{64} << 20);
  // Every Allocation must be gone first.
  ~MemoryAllocator();
  MemoryAllocator(const MemoryAllocator&) = delete;
  MemoryAllocator& operator=(const MemoryAllocator&) = delete;

  // Memory for `requirements` with all of `properties` (e.g. DEVICE_LOCAL, or HOST_VISIBLE |
  // HOST_COHERENT). Throws plumb::Error when the device is out of memory.
  Allocation allocate(const VkMemoryRequirements& requirements, VkMemoryPropertyFlags properties);

  std::size_t blockCount() const;      // device allocations held
  VkDeviceSize bytesInUse() const;     // in live allocations
  VkDeviceSize bytesReserved() const;  // in blocks

 private:
  friend class Allocation;
  struct Block {
    VkDeviceMemory memory = VK_NULL_HANDLE;
    std::uint32_t type = 0;
    VkDeviceSize size = 0;
    VkDeviceSize used = 0;
    std::byte* mapped = nullptr;
    std::map<VkDeviceSize, VkDeviceSize> free;  // offset -> size, neighbours merged
  };
  void release(std::size_t block, VkDeviceSize offset, VkDeviceSize size);
  std::size_t newBlock(std::uint32_t type, VkDeviceSize size);
  void freeBlock(std::size_t block);

  const Device& device_;
  VkDeviceSize block_size_;
  mutable std::mutex mutex_;
  std::vector<std::unique_ptr<Block>> blocks_;  // null where a block was freed (indices stay valid)
};

}  // namespace plumb::gpu
