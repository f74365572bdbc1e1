#pragma once
// The application's Vulkan device as the session's XrGraphicsBindingVulkan2KHR names it, and the
// one-off command submissions the simulated headset makes on that binding's queue (OpenXR 1.0
// specification, chapter 12, section "XR_KHR_vulkan_enable2": the runtime may use the queue during
// xrCreateSwapchain, xrDestroySwapchain and xrEndFrame, and the application synchronises its own
// use of it with those calls). Vulkan is called through the loader's exported entry points.

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>

#include "tests/support/xr_headset/xr_api.h"

namespace plumb::xr_headset {

struct VulkanBinding {
  VkInstance instance = VK_NULL_HANDLE;
  VkPhysicalDevice physical_device = VK_NULL_HANDLE;
  VkDevice device = VK_NULL_HANDLE;
  std::uint32_t queue_family_index = 0;
  std::uint32_t queue_index = 0;
  VkQueue queue = VK_NULL_HANDLE;
};

// False, after one "simulated headset: <call> failed ..." line on stderr, unless `result` is VK_SUCCESS.
bool vulkanSucceeded(VkResult result, const char* call);

// A memory type in `type_bits` with all of `required`, one that also has `preferred` if there is
// one; nullopt if none has `required`.
std::optional<std::uint32_t> findMemoryType(VkPhysicalDevice physical_device, std::uint32_t type_bits,
                                            VkMemoryPropertyFlags required, VkMemoryPropertyFlags preferred);

// One command buffer from a pool of its own on the binding's queue family, and a fence: every
// submission waits for completion before returning, so nothing the runtime records outlives the
// call that recorded it.
class OneShotCommands {
 public:
  // Null on failure (reported on stderr).
  static std::unique_ptr<OneShotCommands> create(const VulkanBinding& binding);
  ~OneShotCommands();
  OneShotCommands(const OneShotCommands&) = delete;
  OneShotCommands& operator=(const OneShotCommands&) = delete;

  // Records with `record`, submits on the binding's queue and waits for the fence. False on
  // failure (reported on stderr).
  bool run(const std::function<void(VkCommandBuffer)>& record);

 private:
  explicit OneShotCommands(const VulkanBinding& binding) : binding_(binding) {}

  VulkanBinding binding_;
  VkCommandPool pool_ = VK_NULL_HANDLE;
  VkCommandBuffer buffer_ = VK_NULL_HANDLE;
  VkFence fence_ = VK_NULL_HANDLE;
};

}  // namespace plumb::xr_headset
