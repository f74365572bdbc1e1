#include "engine/render/render_target.h"

namespace plumb::render {

namespace {
constexpr VkBufferUsageFlags kUsage =
    VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT;
}

RenderTarget::RenderTarget(const gpu::Device& device, gpu::MemoryAllocator& allocator, std::uint32_t width_px,
                           std::uint32_t height_px)
    : width(width_px),
      height(height_px),
      visibility(device, allocator, pixels() * 8, kUsage, gpu::kDeviceMemory, "visibility"),
      resolved(device, allocator, pixels() * 8, kUsage, gpu::kDeviceMemory, "resolved visibility"),
      colour(device, allocator, pixels() * 4, kUsage, gpu::kDeviceMemory, "colour"),
      colour_image(
          device, width_px, height_px, kColourFormat,
          VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT,
          "colour image") {}

}  // namespace plumb::render
