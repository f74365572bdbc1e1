#pragma once
// A 2-D colour image with its own device memory and a view (move-only RAII). Images are few
// (render targets), so each takes a dedicated allocation: MemoryAllocator serves buffers only.
//
// Destroying an image that a frame in flight uses is a bug: hand it to the DeletionQueue.

#include <vulkan/vulkan.h>

#include <cstdint>

namespace plumb::gpu {

class Device;

// A 2-D view of mip 0, layer 0 of `image` (`aspect`: colour or depth); the caller destroys it.
// Throws plumb::Error naming `name`.
VkImageView createImageView(VkDevice device, VkImage image, VkFormat format, VkImageAspectFlags aspect,
                            const char* name);

class Image {
 public:
  Image() = default;
  // Throws plumb::Error when the device is out of memory or lacks the format for `usage`.
  Image(const Device& device, std::uint32_t width, std::uint32_t height, VkFormat format, VkImageUsageFlags usage,
        const char* name);
  ~Image();
  Image(Image&& other) noexcept;
  Image& operator=(Image&& other) noexcept;
  Image(const Image&) = delete;
  Image& operator=(const Image&) = delete;

  VkImage handle() const { return image_; }
  VkImageView view() const { return view_; }
  VkFormat format() const { return format_; }
  std::uint32_t width() const { return width_; }
  std::uint32_t height() const { return height_; }
  explicit operator bool() const { return image_ != VK_NULL_HANDLE; }

 private:
  void destroy();

  VkDevice device_ = VK_NULL_HANDLE;
  VkImage image_ = VK_NULL_HANDLE;
  VkImageView view_ = VK_NULL_HANDLE;
  VkDeviceMemory memory_ = VK_NULL_HANDLE;
  VkFormat format_ = VK_FORMAT_UNDEFINED;
  std::uint32_t width_ = 0, height_ = 0;
};

}  // namespace plumb::gpu
