#include "engine/gpu/swapchain.h"

#include <algorithm>
#include <limits>
#include <string>

#include "engine/gpu/device.h"
#include "engine/gpu/instance.h"
#include "engine/gpu/vk_check.h"

namespace plumb::gpu {
namespace {

VkSemaphore createSemaphore(VkDevice device) {
  VkSemaphoreCreateInfo create{};
  create.sType = VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO;
  VkSemaphore semaphore = VK_NULL_HANDLE;
  check(vkCreateSemaphore(device, &create, nullptr, &semaphore), "vkCreateSemaphore");
  return semaphore;
}

// 8-bit UNORM BGRA or RGBA, which the renderer blits into; the first format otherwise.
VkSurfaceFormatKHR chooseFormat(VkPhysicalDevice physical, VkSurfaceKHR surface) {
  std::uint32_t count = 0;
  check(vkGetPhysicalDeviceSurfaceFormatsKHR(physical, surface, &count, nullptr),
        "vkGetPhysicalDeviceSurfaceFormatsKHR");
  std::vector<VkSurfaceFormatKHR> formats(count);
  check(vkGetPhysicalDeviceSurfaceFormatsKHR(physical, surface, &count, formats.data()),
        "vkGetPhysicalDeviceSurfaceFormatsKHR", VK_INCOMPLETE);
  if (formats.empty()) throw Error("the window's surface offers no formats");
  for (const VkSurfaceFormatKHR& format : formats) {
    if (format.format == VK_FORMAT_B8G8R8A8_UNORM || format.format == VK_FORMAT_R8G8B8A8_UNORM) return format;
  }
  return formats.front();
}

}  // namespace

Swapchain::Swapchain(const Instance& instance, const Device& device, VkSurfaceKHR surface,
                     std::function<VkExtent2D()> framebuffer_size)
    : instance_(instance.handle()),
      device_(device),
      surface_(surface),
      framebuffer_size_(std::move(framebuffer_size)),
      surface_format_(chooseFormat(device.physical(), surface)),
      format_(surface_format_.format) {}

Swapchain::~Swapchain() {
  vkDeviceWaitIdle(device_.handle());  // presentation may still read the images
  destroyImagesAndSemaphores();
  if (swapchain_ != VK_NULL_HANDLE) vkDestroySwapchainKHR(device_.handle(), swapchain_, nullptr);
  vkDestroySurfaceKHR(instance_, surface_, nullptr);
}

void Swapchain::destroyImagesAndSemaphores() {
  for (VkSemaphore semaphore : acquired_) vkDestroySemaphore(device_.handle(), semaphore, nullptr);
  for (VkSemaphore semaphore : rendered_) vkDestroySemaphore(device_.handle(), semaphore, nullptr);
  acquired_.clear();
  rendered_.clear();
  images_.clear();
}

void Swapchain::build() {
  const VkExtent2D wanted = framebuffer_size_();
  VkSurfaceCapabilitiesKHR capabilities;
  check(vkGetPhysicalDeviceSurfaceCapabilitiesKHR(device_.physical(), surface_, &capabilities),
        "vkGetPhysicalDeviceSurfaceCapabilitiesKHR");
  VkExtent2D extent = capabilities.currentExtent;
  if (extent.width == std::numeric_limits<std::uint32_t>::max()) {  // the window lets the swapchain decide
    extent.width = std::clamp(wanted.width, capabilities.minImageExtent.width, capabilities.maxImageExtent.width);
    extent.height = std::clamp(wanted.height, capabilities.minImageExtent.height, capabilities.maxImageExtent.height);
  }
  if (extent.width == 0 || extent.height == 0) return;  // minimised: stays stale

  vkDeviceWaitIdle(device_.handle());  // the old images may be in use
  const VkSurfaceFormatKHR& format = surface_format_;
  std::uint32_t image_count = std::max(capabilities.minImageCount + 1, 2u);
  if (capabilities.maxImageCount > 0) image_count = std::min(image_count, capabilities.maxImageCount);

  VkSwapchainCreateInfoKHR create{};
  create.sType = VK_STRUCTURE_TYPE_SWAPCHAIN_CREATE_INFO_KHR;
  create.surface = surface_;
  create.minImageCount = image_count;
  create.imageFormat = format.format;
  create.imageColorSpace = format.colorSpace;
  create.imageExtent = extent;
  create.imageArrayLayers = 1;
  // Transfer source too where the surface allows it: the viewer's screenshots read the image.
  readable_ = (capabilities.supportedUsageFlags & VK_IMAGE_USAGE_TRANSFER_SRC_BIT) != 0;
  create.imageUsage = VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT |
                      (readable_ ? VkImageUsageFlags{VK_IMAGE_USAGE_TRANSFER_SRC_BIT} : VkImageUsageFlags{0});
  create.imageSharingMode = VK_SHARING_MODE_EXCLUSIVE;
  create.preTransform = capabilities.currentTransform;
  create.compositeAlpha = VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR;
  create.presentMode = VK_PRESENT_MODE_FIFO_KHR;  // always available; no tearing
  create.clipped = VK_TRUE;
  create.oldSwapchain = swapchain_;
  VkSwapchainKHR created = VK_NULL_HANDLE;
  check(vkCreateSwapchainKHR(device_.handle(), &create, nullptr, &created), "vkCreateSwapchainKHR");
  destroyImagesAndSemaphores();
  if (swapchain_ != VK_NULL_HANDLE) vkDestroySwapchainKHR(device_.handle(), swapchain_, nullptr);
  swapchain_ = created;
  device_.setName(VK_OBJECT_TYPE_SWAPCHAIN_KHR, swapchain_, "swapchain");

  std::uint32_t count = 0;
  check(vkGetSwapchainImagesKHR(device_.handle(), swapchain_, &count, nullptr), "vkGetSwapchainImagesKHR");
  images_.resize(count);
  check(vkGetSwapchainImagesKHR(device_.handle(), swapchain_, &count, images_.data()), "vkGetSwapchainImagesKHR",
        VK_INCOMPLETE);
  for (std::uint32_t i = 0; i <= count; ++i) acquired_.push_back(createSemaphore(device_.handle()));
  for (std::uint32_t i = 0; i < count; ++i) rendered_.push_back(createSemaphore(device_.handle()));
  next_acquired_ = 0;
  format_ = format.format;
  extent_ = extent;
  stale_ = false;
  if (builds_++ > 0) ++rebuilds_;
}

std::optional<SwapchainImage> Swapchain::acquire() {
  const VkExtent2D size = framebuffer_size_();
  if (size.width == 0 || size.height == 0) return std::nullopt;  // minimised
  if (size.width != extent_.width || size.height != extent_.height) stale_ = true;
  for (int attempt = 0; attempt < 2; ++attempt) {
    if (stale_) build();
    if (stale_) return std::nullopt;  // the surface reports no area yet
    const VkSemaphore acquired = acquired_[next_acquired_];
    std::uint32_t index = 0;
    const VkResult result = vkAcquireNextImageKHR(
        device_.handle(), swapchain_, std::numeric_limits<std::uint64_t>::max(), acquired, VK_NULL_HANDLE, &index);
    if (result == VK_ERROR_OUT_OF_DATE_KHR) {
      stale_ = true;
      continue;
    }
    check(result, "vkAcquireNextImageKHR", VK_SUBOPTIMAL_KHR);
    if (result == VK_SUBOPTIMAL_KHR) stale_ = true;  // this image still presents; rebuild next time
    next_acquired_ = (next_acquired_ + 1) % acquired_.size();
    return SwapchainImage{images_[index], index, extent_, format_, acquired, rendered_[index]};
  }
  return std::nullopt;
}

void Swapchain::present(const SwapchainImage& image) {
  VkPresentInfoKHR present{};
  present.sType = VK_STRUCTURE_TYPE_PRESENT_INFO_KHR;
  present.waitSemaphoreCount = 1;
  present.pWaitSemaphores = &image.rendered;
  present.swapchainCount = 1;
  present.pSwapchains = &swapchain_;
  present.pImageIndices = &image.index;
  const VkResult result = vkQueuePresentKHR(device_.queue(), &present);
  if (result == VK_ERROR_OUT_OF_DATE_KHR || result == VK_SUBOPTIMAL_KHR) {
    stale_ = true;
    return;
  }
  check(result, "vkQueuePresentKHR");
}

}  // namespace plumb::gpu
