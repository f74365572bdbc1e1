#pragma once
// A VkBuffer with its memory from MemoryAllocator (move-only RAII). Every buffer may be read by
// shaders through its device address: the renderer passes addresses in push constants instead of
// descriptor sets, which sidesteps lavapipe's 128 MiB storage range and its lack of descriptor
// indexing.
//
// Destroying a buffer that a frame in flight uses is a bug: hand it to the DeletionQueue instead.

#include <vulkan/vulkan.h>

#include "engine/gpu/memory.h"

namespace plumb::gpu {

class Device;

// Memory the host writes and reads through a pointer (staging, readback, per-frame records).
constexpr VkMemoryPropertyFlags kHostMemory =
    VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
// Memory for the GPU only (on lavapipe it is host-visible too, which nothing relies on).
constexpr VkMemoryPropertyFlags kDeviceMemory = VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT;

class Buffer {
 public:
  Buffer() = default;
  // `size` > 0 bytes; `usage` gains SHADER_DEVICE_ADDRESS. `name` shows in validation messages.
  // Throws plumb::Error when the device is out of memory.
  Buffer(const Device& device, MemoryAllocator& allocator, VkDeviceSize size, VkBufferUsageFlags usage,
         VkMemoryPropertyFlags properties, const char* name);
  ~Buffer();
  Buffer(Buffer&& other) noexcept;
  Buffer& operator=(Buffer&& other) noexcept;
  Buffer(const Buffer&) = delete;
  Buffer& operator=(const Buffer&) = delete;

  VkBuffer handle() const { return buffer_; }
  VkDeviceSize size() const { return size_; }
  VkDeviceAddress address() const { return address_; }
  // The first byte in host memory; null unless the memory is host-visible.
  void* mapped() const { return allocation_.mapped(); }
  explicit operator bool() const { return buffer_ != VK_NULL_HANDLE; }

 private:
  void destroy();

  VkDevice device_ = VK_NULL_HANDLE;
  VkBuffer buffer_ = VK_NULL_HANDLE;
  VkDeviceSize size_ = 0;
  VkDeviceAddress address_ = 0;
  Allocation allocation_;
};

}  // namespace plumb::gpu
