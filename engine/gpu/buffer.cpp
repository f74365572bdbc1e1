#include "engine/gpu/buffer.h"

#include <utility>

#include "engine/gpu/device.h"
#include "engine/gpu/vk_check.h"

namespace plumb::gpu {

Buffer::Buffer(const Device& device, MemoryAllocator& allocator, VkDeviceSize size, VkBufferUsageFlags usage,
               VkMemoryPropertyFlags properties, const char* name)
    : device_(device.handle()), size_(size) {
  VkBufferCreateInfo create{};
  create.sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO;
  create.size = size;
  create.usage = usage | VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT;
  check(vkCreateBuffer(device_, &create, nullptr, &buffer_), std::string("vkCreateBuffer (") + name + ")");
  device.setName(VK_OBJECT_TYPE_BUFFER, buffer_, name);
  try {
    VkMemoryRequirements requirements;
    vkGetBufferMemoryRequirements(device_, buffer_, &requirements);
    allocation_ = allocator.allocate(requirements, properties);
    check(vkBindBufferMemory(device_, buffer_, allocation_.memory(), allocation_.offset()), "vkBindBufferMemory");
  } catch (...) {
    destroy();
    throw;
  }
  VkBufferDeviceAddressInfo address{};
  address.sType = VK_STRUCTURE_TYPE_BUFFER_DEVICE_ADDRESS_INFO;
  address.buffer = buffer_;
  address_ = vkGetBufferDeviceAddress(device_, &address);
}

Buffer::~Buffer() {
  destroy();
}

Buffer::Buffer(Buffer&& other) noexcept
    : device_(other.device_),
      buffer_(std::exchange(other.buffer_, VK_NULL_HANDLE)),
      size_(std::exchange(other.size_, 0)),
      address_(std::exchange(other.address_, 0)),
      allocation_(std::move(other.allocation_)) {}

Buffer& Buffer::operator=(Buffer&& other) noexcept {
  if (this != &other) {
    destroy();
    device_ = other.device_;
    buffer_ = std::exchange(other.buffer_, VK_NULL_HANDLE);
    size_ = std::exchange(other.size_, 0);
    address_ = std::exchange(other.address_, 0);
    allocation_ = std::move(other.allocation_);
  }
  return *this;
}

void Buffer::destroy() {
  if (buffer_ != VK_NULL_HANDLE) vkDestroyBuffer(device_, buffer_, nullptr);
  buffer_ = VK_NULL_HANDLE;
  allocation_ = Allocation();
}

}  // namespace plumb::gpu
