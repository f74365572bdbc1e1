// The readback of a released colour image (image_readback.h):
//
//   1. A host-visible buffer of the region's size.
//   2. One command buffer on the binding's queue: a barrier from everything the application did
//      (ALL_COMMANDS, MEMORY_WRITE) to the copy, COLOR_ATTACHMENT_OPTIMAL -> TRANSFER_SRC_OPTIMAL;
//      vkCmdCopyImageToBuffer; the image back to COLOR_ATTACHMENT_OPTIMAL for whatever the
//      application does next; the buffer's writes made visible to the host.
//   3. Submit, wait for the fence, copy the bytes out (swizzling BGRA).
// Vulkan 1.0 barriers only (vkCmdPipelineBarrier): the application's device may not enable
// synchronization2.

#include "tests/support/xr_headset/image_readback.h"

#include <cstdio>
#include <cstring>
#include <utility>

namespace plumb::xr_headset {
namespace {

// A buffer and its memory, freed when it goes out of scope.
struct HostBuffer {
  VkDevice device = VK_NULL_HANDLE;
  VkBuffer buffer = VK_NULL_HANDLE;
  VkDeviceMemory memory = VK_NULL_HANDLE;
  bool coherent = false;

  explicit HostBuffer(VkDevice owner) : device(owner) {}
  ~HostBuffer() {
    if (buffer != VK_NULL_HANDLE) vkDestroyBuffer(device, buffer, nullptr);
    if (memory != VK_NULL_HANDLE) vkFreeMemory(device, memory, nullptr);
  }
  HostBuffer(const HostBuffer&) = delete;
  HostBuffer& operator=(const HostBuffer&) = delete;
};

bool createHostBuffer(const VulkanBinding& binding, VkDeviceSize size, HostBuffer& host) {
  VkBufferCreateInfo buffer_info{};
  buffer_info.sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO;
  buffer_info.size = size;
  buffer_info.usage = VK_BUFFER_USAGE_TRANSFER_DST_BIT;
  buffer_info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  if (!vulkanSucceeded(vkCreateBuffer(binding.device, &buffer_info, nullptr, &host.buffer), "vkCreateBuffer")) {
    return false;
  }
  VkMemoryRequirements requirements{};
  vkGetBufferMemoryRequirements(binding.device, host.buffer, &requirements);
  const std::optional<std::uint32_t> type =
      findMemoryType(binding.physical_device, requirements.memoryTypeBits, VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT,
                     VK_MEMORY_PROPERTY_HOST_COHERENT_BIT);
  if (!type) {
    std::fprintf(stderr, "simulated headset: the device has no host-visible memory for the readback\n");
    return false;
  }
  VkPhysicalDeviceMemoryProperties properties{};
  vkGetPhysicalDeviceMemoryProperties(binding.physical_device, &properties);
  host.coherent = (properties.memoryTypes[*type].propertyFlags & VK_MEMORY_PROPERTY_HOST_COHERENT_BIT) != 0;
  VkMemoryAllocateInfo allocate{};
  allocate.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO;
  allocate.allocationSize = requirements.size;
  allocate.memoryTypeIndex = *type;
  if (!vulkanSucceeded(vkAllocateMemory(binding.device, &allocate, nullptr, &host.memory), "vkAllocateMemory")) {
    return false;
  }
  return vulkanSucceeded(vkBindBufferMemory(binding.device, host.buffer, host.memory, 0), "vkBindBufferMemory");
}

VkImageMemoryBarrier layoutChange(VkImage image, VkImageAspectFlags aspect, std::uint32_t array_layer,
                                  VkImageLayout from, VkImageLayout to, VkAccessFlags src_access,
                                  VkAccessFlags dst_access) {
  VkImageMemoryBarrier barrier{};
  barrier.sType = VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER;
  barrier.srcAccessMask = src_access;
  barrier.dstAccessMask = dst_access;
  barrier.oldLayout = from;
  barrier.newLayout = to;
  barrier.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  barrier.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  barrier.image = image;
  barrier.subresourceRange = {aspect, 0, 1, array_layer, 1};
  return barrier;
}

// Copies `rect` of an image's `aspect` (in `held`, its layout between the application's uses,
// where it is left) into `bytes`, `pixel_bytes` a pixel, rows top to bottom.
bool readImage(const VulkanBinding& binding, OneShotCommands& commands, VkImage image, VkImageAspectFlags aspect,
               VkImageLayout held, VkAccessFlags held_access, std::uint32_t array_layer, const XrRect2Di& rect,
               std::uint32_t pixel_bytes, std::vector<std::uint8_t>& bytes) {
  const auto width = static_cast<std::uint32_t>(rect.extent.width);
  const auto height = static_cast<std::uint32_t>(rect.extent.height);
  const VkDeviceSize size = VkDeviceSize{width} * height * pixel_bytes;

  // 1. The buffer.
  HostBuffer host(binding.device);
  if (!createHostBuffer(binding, size, host)) return false;

  // 2. The commands.
  const bool copied = commands.run([&](VkCommandBuffer command_buffer) {
    const VkImageMemoryBarrier to_copy =
        layoutChange(image, aspect, array_layer, held, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_ACCESS_MEMORY_WRITE_BIT,
                     VK_ACCESS_TRANSFER_READ_BIT);
    vkCmdPipelineBarrier(command_buffer, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 0,
                         nullptr, 0, nullptr, 1, &to_copy);
    VkBufferImageCopy region{};
    region.imageSubresource = {aspect, 0, array_layer, 1};
    region.imageOffset = {rect.offset.x, rect.offset.y, 0};
    region.imageExtent = {width, height, 1};
    vkCmdCopyImageToBuffer(command_buffer, image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, host.buffer, 1, &region);
    // The copy only read the image: an execution dependency orders the application's later
    // writes after it, and the layout change is made visible to attachment use (anything else the
    // application does next starts with a barrier of its own).
    const VkImageMemoryBarrier back =
        layoutChange(image, aspect, array_layer, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, held, 0, held_access);
    vkCmdPipelineBarrier(command_buffer, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, 0, 0,
                         nullptr, 0, nullptr, 1, &back);
    VkBufferMemoryBarrier to_host{};
    to_host.sType = VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER;
    to_host.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
    to_host.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
    to_host.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    to_host.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    to_host.buffer = host.buffer;
    to_host.offset = 0;
    to_host.size = VK_WHOLE_SIZE;
    vkCmdPipelineBarrier(command_buffer, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 0, nullptr, 1,
                         &to_host, 0, nullptr);
  });
  if (!copied) return false;

  // 3. The bytes.
  void* mapped = nullptr;
  if (!vulkanSucceeded(vkMapMemory(binding.device, host.memory, 0, VK_WHOLE_SIZE, 0, &mapped), "vkMapMemory")) {
    return false;
  }
  if (!host.coherent) {
    VkMappedMemoryRange range{};
    range.sType = VK_STRUCTURE_TYPE_MAPPED_MEMORY_RANGE;
    range.memory = host.memory;
    range.size = VK_WHOLE_SIZE;
    if (!vulkanSucceeded(vkInvalidateMappedMemoryRanges(binding.device, 1, &range), "vkInvalidateMappedMemoryRanges")) {
      vkUnmapMemory(binding.device, host.memory);
      return false;
    }
  }
  bytes.resize(static_cast<std::size_t>(size));
  std::memcpy(bytes.data(), mapped, bytes.size());
  vkUnmapMemory(binding.device, host.memory);
  return true;
}

}  // namespace

bool readColorImage(const VulkanBinding& binding, OneShotCommands& commands, VkImage image, VkFormat format,
                    std::uint32_t array_layer, const XrRect2Di& rect, std::vector<std::uint8_t>& rgba) {
  if (!readImage(binding, commands, image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                 VK_ACCESS_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT, array_layer, rect, 4,
                 rgba)) {
    return false;
  }
  if (format == VK_FORMAT_B8G8R8A8_SRGB || format == VK_FORMAT_B8G8R8A8_UNORM) {
    for (std::size_t i = 0; i < rgba.size(); i += 4) std::swap(rgba[i], rgba[i + 2]);
  }
  return true;
}

bool readDepthImage(const VulkanBinding& binding, OneShotCommands& commands, VkImage image, VkFormat format,
                    std::uint32_t array_layer, const XrRect2Di& rect, std::vector<float>& depths) {
  const bool wide = format == VK_FORMAT_D32_SFLOAT;
  if (!wide && format != VK_FORMAT_D16_UNORM) {
    std::fprintf(stderr, "simulated headset: depth of format %d is not read back (D32_SFLOAT, D16_UNORM are)\n",
                 static_cast<int>(format));
    return false;
  }
  std::vector<std::uint8_t> bytes;
  if (!readImage(binding, commands, image, VK_IMAGE_ASPECT_DEPTH_BIT, VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL,
                 VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_READ_BIT | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT,
                 array_layer, rect, wide ? 4 : 2, bytes)) {
    return false;
  }
  depths.resize(bytes.size() / (wide ? 4 : 2));
  for (std::size_t i = 0; i < depths.size(); ++i) {
    if (wide) {
      std::memcpy(&depths[i], bytes.data() + 4 * i, 4);
    } else {
      std::uint16_t unorm = 0;
      std::memcpy(&unorm, bytes.data() + 2 * i, 2);
      depths[i] = static_cast<float>(unorm) / 65535.0f;
    }
  }
  return true;
}

}  // namespace plumb::xr_headset
