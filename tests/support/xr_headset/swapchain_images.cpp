// Swapchain images on the application's device (swapchain_images.h). OpenXR 1.0 specification,
// chapter 12, section "XR_KHR_vulkan_enable2": the usage flags map one to one onto Vulkan's and the
// images may have more usage than asked for; images are in COLOR_ATTACHMENT_OPTIMAL (colour) or
// DEPTH_STENCIL_ATTACHMENT_OPTIMAL (depth) whenever the application holds them.
//
//   1. Usage: the application's, plus TRANSFER_SRC (the readback in xrEndFrame) and the attachment
//      usage of the format's handover layout (a layout the image's usage must allow).
//   2. The device's limits for that format and usage (vkGetPhysicalDeviceImageFormatProperties).
//   3. Images and their memory, device-local where there is such memory.
//   4. One submission moving every image from UNDEFINED to the handover layout.

#include "tests/support/xr_headset/swapchain_images.h"

#include <array>
#include <cstdio>

namespace plumb::xr_headset {
namespace {

constexpr std::array kSwapchainFormats{VK_FORMAT_R8G8B8A8_SRGB,  VK_FORMAT_R8G8B8A8_UNORM, VK_FORMAT_B8G8R8A8_SRGB,
                                       VK_FORMAT_B8G8R8A8_UNORM, VK_FORMAT_D32_SFLOAT,     VK_FORMAT_D16_UNORM};

VkImageUsageFlags vulkanUsage(XrSwapchainUsageFlags usage, VkFormat format) {
  VkImageUsageFlags result = VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
  if (isDepthFormat(format)) {
    result |= VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT;
  } else {
    result |= VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT;
  }
  if ((usage & XR_SWAPCHAIN_USAGE_UNORDERED_ACCESS_BIT) != 0) result |= VK_IMAGE_USAGE_STORAGE_BIT;
  if ((usage & XR_SWAPCHAIN_USAGE_TRANSFER_DST_BIT) != 0) result |= VK_IMAGE_USAGE_TRANSFER_DST_BIT;
  if ((usage & XR_SWAPCHAIN_USAGE_SAMPLED_BIT) != 0) result |= VK_IMAGE_USAGE_SAMPLED_BIT;
  if ((usage & XR_SWAPCHAIN_USAGE_INPUT_ATTACHMENT_BIT_KHR) != 0) result |= VK_IMAGE_USAGE_INPUT_ATTACHMENT_BIT;
  return result;
}

VkImageAspectFlags aspectOf(VkFormat format) {
  return isDepthFormat(format) ? VK_IMAGE_ASPECT_DEPTH_BIT : VK_IMAGE_ASPECT_COLOR_BIT;
}

// What the application may do to an image in its handover layout, without a barrier of its own.
VkAccessFlags attachmentAccess(VkFormat format) {
  if (isDepthFormat(format)) {
    return VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_READ_BIT | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT;
  }
  return VK_ACCESS_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
}

XrResult unsupported(const char* why, VkFormat format) {
  std::fprintf(stderr, "simulated headset: xrCreateSwapchain: %s (VkFormat %d)\n", why, static_cast<int>(format));
  return XR_ERROR_SWAPCHAIN_FORMAT_UNSUPPORTED;
}

}  // namespace

std::span<const VkFormat> swapchainFormats() {
  return kSwapchainFormats;
}

bool isDepthFormat(VkFormat format) {
  return format == VK_FORMAT_D32_SFLOAT || format == VK_FORMAT_D16_UNORM;
}

bool isReadableColorFormat(VkFormat format) {
  return format == VK_FORMAT_R8G8B8A8_SRGB || format == VK_FORMAT_R8G8B8A8_UNORM || format == VK_FORMAT_B8G8R8A8_SRGB ||
         format == VK_FORMAT_B8G8R8A8_UNORM;
}

VkImageLayout handoverLayout(VkFormat format) {
  return isDepthFormat(format) ? VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL
                               : VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
}

XrResult SwapchainImages::create(const VulkanBinding& binding, OneShotCommands& commands,
                                 const SwapchainImageSpec& spec, std::unique_ptr<SwapchainImages>& created) {
  // 1. Usage.
  const VkImageUsageFlags usage = vulkanUsage(spec.usage, spec.format);
  const VkImageCreateFlags flags =
      (spec.usage & XR_SWAPCHAIN_USAGE_MUTABLE_FORMAT_BIT) != 0 ? VK_IMAGE_CREATE_MUTABLE_FORMAT_BIT : 0;

  // 2. Limits.
  VkImageFormatProperties limits{};
  if (vkGetPhysicalDeviceImageFormatProperties(binding.physical_device, spec.format, VK_IMAGE_TYPE_2D,
                                               VK_IMAGE_TILING_OPTIMAL, usage, flags, &limits) != VK_SUCCESS) {
    return unsupported("the device cannot make images of this format with this usage", spec.format);
  }
  if (spec.width > limits.maxExtent.width || spec.height > limits.maxExtent.height ||
      spec.array_size > limits.maxArrayLayers || spec.mip_count > limits.maxMipLevels) {
    return unsupported("the size, array size or mip count is beyond the device's limits", spec.format);
  }

  // 3. Images and memory.
  std::unique_ptr<SwapchainImages> images(new SwapchainImages(binding));
  for (std::uint32_t i = 0; i < spec.image_count; ++i) {
    VkImageCreateInfo image_info{};
    image_info.sType = VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO;
    image_info.flags = flags;
    image_info.imageType = VK_IMAGE_TYPE_2D;
    image_info.format = spec.format;
    image_info.extent = {spec.width, spec.height, 1};
    image_info.mipLevels = spec.mip_count;
    image_info.arrayLayers = spec.array_size;
    image_info.samples = VK_SAMPLE_COUNT_1_BIT;
    image_info.tiling = VK_IMAGE_TILING_OPTIMAL;
    image_info.usage = usage;
    image_info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
    image_info.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    VkImage image = VK_NULL_HANDLE;
    if (!vulkanSucceeded(vkCreateImage(binding.device, &image_info, nullptr, &image), "vkCreateImage")) {
      return XR_ERROR_RUNTIME_FAILURE;
    }
    images->images_.push_back(image);

    VkMemoryRequirements requirements{};
    vkGetImageMemoryRequirements(binding.device, image, &requirements);
    const std::optional<std::uint32_t> type =
        findMemoryType(binding.physical_device, requirements.memoryTypeBits, 0, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
    if (!type) {
      std::fprintf(stderr, "simulated headset: xrCreateSwapchain: no memory type can hold the image\n");
      return XR_ERROR_RUNTIME_FAILURE;
    }
    VkMemoryAllocateInfo allocate{};
    allocate.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO;
    allocate.allocationSize = requirements.size;
    allocate.memoryTypeIndex = *type;
    VkDeviceMemory memory = VK_NULL_HANDLE;
    if (!vulkanSucceeded(vkAllocateMemory(binding.device, &allocate, nullptr, &memory), "vkAllocateMemory")) {
      return XR_ERROR_RUNTIME_FAILURE;
    }
    images->memory_.push_back(memory);
    if (!vulkanSucceeded(vkBindImageMemory(binding.device, image, memory, 0), "vkBindImageMemory")) {
      return XR_ERROR_RUNTIME_FAILURE;
    }
  }

  // 4. To the handover layout. Nothing has used the images yet: no source stage to wait for.
  const bool moved = commands.run([&](VkCommandBuffer command_buffer) {
    std::vector<VkImageMemoryBarrier> barriers;
    for (VkImage image : images->images_) {
      VkImageMemoryBarrier barrier{};
      barrier.sType = VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER;
      barrier.srcAccessMask = 0;
      barrier.dstAccessMask = attachmentAccess(spec.format);
      barrier.oldLayout = VK_IMAGE_LAYOUT_UNDEFINED;
      barrier.newLayout = handoverLayout(spec.format);
      barrier.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
      barrier.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
      barrier.image = image;
      barrier.subresourceRange = {aspectOf(spec.format), 0, spec.mip_count, 0, spec.array_size};
      barriers.push_back(barrier);
    }
    vkCmdPipelineBarrier(command_buffer, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, 0, 0,
                         nullptr, 0, nullptr, static_cast<std::uint32_t>(barriers.size()), barriers.data());
  });
  if (!moved) return XR_ERROR_RUNTIME_FAILURE;
  created = std::move(images);
  return XR_SUCCESS;
}

SwapchainImages::~SwapchainImages() {
  if (!images_.empty()) vulkanSucceeded(vkQueueWaitIdle(binding_.queue), "vkQueueWaitIdle");
  for (VkImage image : images_) vkDestroyImage(binding_.device, image, nullptr);
  for (VkDeviceMemory memory : memory_) vkFreeMemory(binding_.device, memory, nullptr);
}

}  // namespace plumb::xr_headset
