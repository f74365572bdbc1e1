#pragma once
// Screenshots of the whole window, palette included: a copy of the presented swapchain image
// into host memory, recorded at the end of a frame's present hook, read once the frame is done.

#include <vulkan/vulkan.h>

#include <optional>

#include "engine/gpu/buffer.h"
#include "engine/io/png_image.h"

namespace plumb::gpu {
class Device;
class MemoryAllocator;
struct SwapchainImage;
}  // namespace plumb::gpu

namespace plumb::viewer {

class ScreenshotCopy {
 public:
  ScreenshotCopy(const gpu::Device& device, gpu::MemoryAllocator& allocator);

  // Records the copy of `image`, which is in PRESENT_SRC_KHR with its colour written (the
  // swapchain must be readable: Swapchain::readable()), and leaves it in PRESENT_SRC_KHR.
  void record(VkCommandBuffer commands, const gpu::SwapchainImage& image);
  // The image copied by the last record(); call once the GPU has finished that frame. Converts
  // the swapchain's BGRA or RGBA to RGBA. Nothing when no copy was recorded since the last take.
  std::optional<io::RgbaImage> take();

 private:
  const gpu::Device& device_;
  gpu::MemoryAllocator& allocator_;
  gpu::Buffer buffer_;
  VkExtent2D extent_{};
  VkFormat format_ = VK_FORMAT_UNDEFINED;
  bool recorded_ = false;
};

}  // namespace plumb::viewer
