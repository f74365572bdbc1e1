#pragma once
// Who makes Plumb's Vulkan instance and device when Plumb does not make them itself. An OpenXR
// runtime must (XR_KHR_vulkan_enable2: xrCreateVulkanInstanceKHR, xrGetVulkanGraphicsDevice2KHR,
// xrCreateVulkanDeviceKHR): it adds what its compositor needs to Plumb's create infos, and it
// names the GPU its headset is on. ui/xr implements this; engine/gpu knows nothing of OpenXR.

#include <vulkan/vulkan.h>

namespace plumb::gpu {

class VulkanFactory {
 public:
  virtual ~VulkanFactory() = default;
  // Each throws plumb::Error saying what failed; none returns a null handle.
  virtual VkInstance createInstance(const VkInstanceCreateInfo& create) = 0;
  virtual VkPhysicalDevice physicalDevice(VkInstance instance) = 0;  // the only one Plumb may use
  virtual VkDevice createDevice(VkPhysicalDevice physical, const VkDeviceCreateInfo& create) = 0;
};

}  // namespace plumb::gpu
