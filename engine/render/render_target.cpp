#include "engine/render/render_target.h"

#include "engine/gpu/commands.h"

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

VkBufferImageCopy RenderTarget::colourRegion() const {
  return {0, 0, 0, {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1}, {0, 0, 0}, {width, height, 1}};
}

void RenderTarget::copyColourToImage(VkCommandBuffer commands, VkImageLayout layout, VkPipelineStageFlags2 next_stages,
                                     VkAccessFlags2 next_access) const {
  gpu::memoryBarrier(commands, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_WRITE_BIT,
                     VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_READ_BIT);
  // The image's old content is not needed, only the previous frame's reads (overlay copy-back,
  // presentation blit) must be over.
  gpu::imageBarrier(commands, colour_image.handle(), VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                    VK_PIPELINE_STAGE_2_COPY_BIT | VK_PIPELINE_STAGE_2_BLIT_BIT, VK_ACCESS_2_TRANSFER_READ_BIT,
                    VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
  const VkBufferImageCopy region = colourRegion();
  vkCmdCopyBufferToImage(commands, colour.handle(), colour_image.handle(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1,
                         &region);
  gpu::imageBarrier(commands, colour_image.handle(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, layout,
                    VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT, next_stages, next_access);
}

}  // namespace plumb::render
