#pragma once
// The headset's OpenXR runtime, found by Khronos' loader (the active runtime's manifest, or
// XR_RUNTIME_JSON): an instance with XR_KHR_vulkan_enable2 and the head-mounted system.
// OpenXR 1.0 specification, sections 4 (instance), 5 (system) and 12.20 (XR_KHR_vulkan_enable2).
//
// It is also the gpu::VulkanFactory of a viewer started for a headset: with
// XR_KHR_vulkan_enable2 the runtime makes the Vulkan instance and device from Plumb's create
// infos (adding what its compositor needs) and names the GPU the headset is on. Sessions
// (xr_session.h) are made and ended on it as the user starts and leaves VR.
//
// Not thread-safe: the viewer's main thread owns it.

#include <openxr/openxr.h>
#include <vulkan/vulkan.h>

#include <string>

#include "engine/gpu/vulkan_factory.h"

namespace plumb::xr {

class Runtime final : public gpu::VulkanFactory {
 public:
  // Throws xr::Error naming what is missing: no runtime installed or active, no headset
  // connected, a runtime that does not drive Vulkan.
  Runtime();
  ~Runtime() override;
  Runtime(const Runtime&) = delete;
  Runtime& operator=(const Runtime&) = delete;

  XrInstance instance() const { return instance_; }
  XrSystemId system() const { return system_; }
  const std::string& name() const { return name_; }  // "<runtime> <version>"
  // Whether projection layers may carry depth (XR_KHR_composition_layer_depth).
  bool depthLayers() const { return depth_layers_; }

  VkInstance createInstance(const VkInstanceCreateInfo& create) override;
  VkPhysicalDevice physicalDevice(VkInstance instance) override;
  VkDevice createDevice(VkPhysicalDevice physical, const VkDeviceCreateInfo& create) override;

 private:
  XrInstance instance_ = XR_NULL_HANDLE;
  XrSystemId system_ = XR_NULL_SYSTEM_ID;
  std::string name_;
  bool depth_layers_ = false;
};

}  // namespace plumb::xr
