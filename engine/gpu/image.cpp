#include "engine/gpu/image.h"

#include <string>
#include <utility>

#include "engine/gpu/device.h"
#include "engine/gpu/vk_check.h"

namespace plumb::gpu {

VkImageView createImageView(VkDevice device, VkImage image, VkFormat format, VkImageAspectFlags aspect,
                            const char* name) {
  VkImageViewCreateInfo create{};
  create.sType = VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO;
  create.image = image;
  create.viewType = VK_IMAGE_VIEW_TYPE_2D;
  create.format = format;
  create.subresourceRange = {aspect, 0, 1, 0, 1};
  VkImageView view = VK_NULL_HANDLE;
  check(vkCreateImageView(device, &create, nullptr, &view), std::string("vkCreateImageView (") + name + ")");
  return view;
}

Image::Image(const Device& device, std::uint32_t width, std::uint32_t height, VkFormat format, VkImageUsageFlags usage,
             const char* name)
    : device_(device.handle()), format_(format), width_(width), height_(height) {
  VkImageCreateInfo create{};
  create.sType = VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO;
  create.imageType = VK_IMAGE_TYPE_2D;
  create.format = format;
  create.extent = {width, height, 1};
  create.mipLevels = 1;
  create.arrayLayers = 1;
  create.samples = VK_SAMPLE_COUNT_1_BIT;
  create.tiling = VK_IMAGE_TILING_OPTIMAL;
  create.usage = usage;
  create.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
  check(vkCreateImage(device_, &create, nullptr, &image_), std::string("vkCreateImage (") + name + ")");
  device.setName(VK_OBJECT_TYPE_IMAGE, image_, name);
  try {
    VkMemoryRequirements requirements;
    vkGetImageMemoryRequirements(device_, image_, &requirements);
    VkMemoryAllocateInfo allocate{};
    allocate.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO;
    allocate.allocationSize = requirements.size;
    allocate.memoryTypeIndex = device.memoryType(requirements.memoryTypeBits, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
    check(vkAllocateMemory(device_, &allocate, nullptr, &memory_), std::string("vkAllocateMemory (") + name + ")");
    check(vkBindImageMemory(device_, image_, memory_, 0), "vkBindImageMemory");
    view_ = createImageView(device_, image_, format, VK_IMAGE_ASPECT_COLOR_BIT, name);
  } catch (...) {
    destroy();
    throw;
  }
}

Image::~Image() {
  destroy();
}

Image::Image(Image&& other) noexcept
    : device_(other.device_),
      image_(std::exchange(other.image_, VK_NULL_HANDLE)),
      view_(std::exchange(other.view_, VK_NULL_HANDLE)),
      memory_(std::exchange(other.memory_, VK_NULL_HANDLE)),
      format_(other.format_),
      width_(other.width_),
      height_(other.height_) {}

Image& Image::operator=(Image&& other) noexcept {
  if (this != &other) {
    destroy();
    device_ = other.device_;
    image_ = std::exchange(other.image_, VK_NULL_HANDLE);
    view_ = std::exchange(other.view_, VK_NULL_HANDLE);
    memory_ = std::exchange(other.memory_, VK_NULL_HANDLE);
    format_ = other.format_;
    width_ = other.width_;
    height_ = other.height_;
  }
  return *this;
}

void Image::destroy() {
  if (view_ != VK_NULL_HANDLE) vkDestroyImageView(device_, view_, nullptr);
  if (image_ != VK_NULL_HANDLE) vkDestroyImage(device_, image_, nullptr);
  if (memory_ != VK_NULL_HANDLE) vkFreeMemory(device_, memory_, nullptr);
  view_ = VK_NULL_HANDLE;
  image_ = VK_NULL_HANDLE;
  memory_ = VK_NULL_HANDLE;
}

}  // namespace plumb::gpu
