#pragma once
// The Vulkan images behind an XrSwapchain (OpenXR 1.0 specification, chapter 10 "Rendering",
// section "Swapchain Image Management"; chapter 12, section "XR_KHR_vulkan_enable2": usage flags
// and the layouts images are handed over in).

#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "tests/support/xr_headset/vulkan_commands.h"

namespace plumb::xr_headset {

// The formats xrEnumerateSwapchainFormats offers, in order of preference.
std::span<const VkFormat> swapchainFormats();
bool isDepthFormat(VkFormat format);
// Whether the runtime can read the format back as RGBA8 bytes (the colour formats it offers).
bool isReadableColorFormat(VkFormat format);

// The layout images are in whenever the application holds them (XR_KHR_vulkan_enable2).
VkImageLayout handoverLayout(VkFormat format);

struct SwapchainImageSpec {
  VkFormat format = VK_FORMAT_UNDEFINED;
  std::uint32_t width = 0, height = 0;
  std::uint32_t array_size = 1, mip_count = 1;
  XrSwapchainUsageFlags usage = 0;
  std::uint32_t image_count = 3;
};

class SwapchainImages {
 public:
  // Creates the images in device-local memory and moves each to handoverLayout() with one
  // submission on the binding's queue. XR_ERROR_SWAPCHAIN_FORMAT_UNSUPPORTED when the device cannot
  // make such images, XR_ERROR_RUNTIME_FAILURE when Vulkan fails (both reported on stderr).
  static XrResult create(const VulkanBinding& binding, OneShotCommands& commands, const SwapchainImageSpec& spec,
                         std::unique_ptr<SwapchainImages>& created);
  // Waits for the queue to go idle (the application's last frames may still read the images), then
  // destroys the images and frees their memory.
  ~SwapchainImages();
  SwapchainImages(const SwapchainImages&) = delete;
  SwapchainImages& operator=(const SwapchainImages&) = delete;

  const std::vector<VkImage>& images() const { return images_; }

 private:
  explicit SwapchainImages(const VulkanBinding& binding) : binding_(binding) {}

  VulkanBinding binding_;
  std::vector<VkImage> images_;
  std::vector<VkDeviceMemory> memory_;
};

}  // namespace plumb::xr_headset
