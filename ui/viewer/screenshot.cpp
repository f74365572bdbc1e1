#include "ui/viewer/screenshot.h"

#include <cstring>
#include <utility>

#include "engine/gpu/commands.h"
#include "engine/gpu/swapchain.h"

namespace plumb::viewer {

ScreenshotCopy::ScreenshotCopy(const gpu::Device& device, gpu::MemoryAllocator& allocator)
    : device_(device), allocator_(allocator) {}

void ScreenshotCopy::record(VkCommandBuffer commands, const gpu::SwapchainImage& image) {
  const VkDeviceSize bytes = VkDeviceSize{4} * image.extent.width * image.extent.height;
  if (!buffer_ || buffer_.size() < bytes) {
    // Only between frames that the caller has waited for (take() follows each record()).
    buffer_ = gpu::Buffer(device_, allocator_, bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT, gpu::kHostMemory,
                          "screenshot readback");
  }
  gpu::imageBarrier(commands, image.image, VK_IMAGE_LAYOUT_PRESENT_SRC_KHR, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                    VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT | VK_PIPELINE_STAGE_2_TRANSFER_BIT,
                    VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_2_TRANSFER_WRITE_BIT,
                    VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_READ_BIT);
  VkBufferImageCopy region{};
  region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
  region.imageExtent = {image.extent.width, image.extent.height, 1};
  vkCmdCopyImageToBuffer(commands, image.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, buffer_.handle(), 1, &region);
  gpu::imageBarrier(commands, image.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_IMAGE_LAYOUT_PRESENT_SRC_KHR,
                    VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_NONE, VK_PIPELINE_STAGE_2_NONE, VK_ACCESS_2_NONE);
  gpu::memoryBarrier(commands, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                     VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT);
  extent_ = image.extent;
  format_ = image.format;
  recorded_ = true;
}

std::optional<io::RgbaImage> ScreenshotCopy::take() {
  if (!std::exchange(recorded_, false)) return std::nullopt;
  io::RgbaImage out;
  out.width = static_cast<int>(extent_.width);
  out.height = static_cast<int>(extent_.height);
  out.rgba.resize(std::size_t{4} * extent_.width * extent_.height);
  std::memcpy(out.rgba.data(), buffer_.mapped(), out.rgba.size());
  const bool bgra = format_ == VK_FORMAT_B8G8R8A8_UNORM || format_ == VK_FORMAT_B8G8R8A8_SRGB;
  for (std::size_t i = 0; i < out.rgba.size(); i += 4) {
    if (bgra) std::swap(out.rgba[i], out.rgba[i + 2]);
    out.rgba[i + 3] = 255;  // the window is opaque whatever the alpha holds
  }
  return out;
}

}  // namespace plumb::viewer
