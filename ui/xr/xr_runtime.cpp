// The runtime's instance and system, and the Vulkan objects it makes.
//
//   1. The loader asked for the runtime's extensions: none answering means no runtime.
//   2. An instance with XR_KHR_vulkan_enable2 (and XR_KHR_composition_layer_depth where offered).
//   3. The head-mounted system: XR_ERROR_FORM_FACTOR_UNAVAILABLE means no headset connected.
//   4. xrGetVulkanGraphicsRequirements2KHR, which the specification requires before a session.

#include "ui/xr/xr_runtime.h"

#define XR_USE_GRAPHICS_API_VULKAN
#include <openxr/openxr_platform.h>

#include <cstring>
#include <vector>

#include "engine/gpu/vk_check.h"
#include "ui/xr/xr_check.h"

// Debian's OpenXR loader 1.0.20 leaks its per-instance bookkeeping (about 1.3 kB a
// xrCreateInstance, whatever the runtime): LeakSanitizer, in sanitizer builds of `plumb`, reads
// this suppression (tests/xr/simulated_headset_test.cpp carries the same for its own process).
extern "C" __attribute__((visibility("default"), used)) const char* __lsan_default_suppressions() {
  return "leak:libopenxr_loader.so\n";
}

namespace plumb::xr {
namespace {

template <typename Function>
Function instanceFunction(XrInstance instance, const char* name) {
  PFN_xrVoidFunction function = nullptr;
  check(xrGetInstanceProcAddr(instance, name, &function), std::string("the runtime's ") + name);
  return reinterpret_cast<Function>(function);
}

std::vector<std::string> runtimeExtensions() {
  std::uint32_t count = 0;
  const XrResult result = xrEnumerateInstanceExtensionProperties(nullptr, 0, &count, nullptr);
  if (XR_FAILED(result)) {
    throw Error("no OpenXR runtime answered (" + resultName(result) +
                "): install one and make it active (Monado, SteamVR, a headset vendor's), or point XR_RUNTIME_JSON "
                "at its manifest");
  }
  std::vector<XrExtensionProperties> properties(count, {XR_TYPE_EXTENSION_PROPERTIES, nullptr, {}, 0});
  check(xrEnumerateInstanceExtensionProperties(nullptr, count, &count, properties.data()), "the runtime's extensions");
  std::vector<std::string> names;
  for (const XrExtensionProperties& extension : properties) names.emplace_back(extension.extensionName);
  return names;
}

bool has(const std::vector<std::string>& names, const char* name) {
  for (const std::string& n : names) {
    if (n == name) return true;
  }
  return false;
}

}  // namespace

Runtime::Runtime() {
  const std::vector<std::string> offered = runtimeExtensions();
  if (!has(offered, XR_KHR_VULKAN_ENABLE2_EXTENSION_NAME)) {
    throw Error("the OpenXR runtime does not drive Vulkan (it lacks " XR_KHR_VULKAN_ENABLE2_EXTENSION_NAME ")");
  }
  std::vector<const char*> extensions{XR_KHR_VULKAN_ENABLE2_EXTENSION_NAME};
  depth_layers_ = has(offered, XR_KHR_COMPOSITION_LAYER_DEPTH_EXTENSION_NAME);
  if (depth_layers_) extensions.push_back(XR_KHR_COMPOSITION_LAYER_DEPTH_EXTENSION_NAME);

  auto create = xrStruct<XrInstanceCreateInfo>(XR_TYPE_INSTANCE_CREATE_INFO);
  std::strncpy(create.applicationInfo.applicationName, "Plumb", XR_MAX_APPLICATION_NAME_SIZE - 1);
  std::strncpy(create.applicationInfo.engineName, "Plumb", XR_MAX_ENGINE_NAME_SIZE - 1);
  create.applicationInfo.apiVersion = XR_CURRENT_API_VERSION;
  create.enabledExtensionCount = static_cast<std::uint32_t>(extensions.size());
  create.enabledExtensionNames = extensions.data();
  check(xrCreateInstance(&create, &instance_), "starting the OpenXR runtime (xrCreateInstance)");

  try {
    auto properties = xrStruct<XrInstanceProperties>(XR_TYPE_INSTANCE_PROPERTIES);
    check(xrGetInstanceProperties(instance_, &properties), "xrGetInstanceProperties");
    name_ = std::string(properties.runtimeName) + " " + std::to_string(XR_VERSION_MAJOR(properties.runtimeVersion)) +
            "." + std::to_string(XR_VERSION_MINOR(properties.runtimeVersion)) + "." +
            std::to_string(XR_VERSION_PATCH(properties.runtimeVersion));

    auto system = xrStruct<XrSystemGetInfo>(XR_TYPE_SYSTEM_GET_INFO);
    system.formFactor = XR_FORM_FACTOR_HEAD_MOUNTED_DISPLAY;
    const XrResult found = xrGetSystem(instance_, &system, &system_);
    if (found == XR_ERROR_FORM_FACTOR_UNAVAILABLE) {
      throw Error("no headset is connected to " + name_ + " (XR_ERROR_FORM_FACTOR_UNAVAILABLE): connect it and retry");
    }
    check(found, "finding the headset (xrGetSystem)");

    auto requirements = xrStruct<XrGraphicsRequirementsVulkan2KHR>(XR_TYPE_GRAPHICS_REQUIREMENTS_VULKAN2_KHR);
    check(instanceFunction<PFN_xrGetVulkanGraphicsRequirements2KHR>(instance_, "xrGetVulkanGraphicsRequirements2KHR")(
              instance_, system_, &requirements),
          "xrGetVulkanGraphicsRequirements2KHR");
    if (requirements.minApiVersionSupported > XR_MAKE_VERSION(1, 3, 0)) {
      throw Error(name_ + " needs a newer Vulkan than Plumb's 1.3");
    }
  } catch (...) {
    xrDestroyInstance(instance_);
    throw;
  }
}

Runtime::~Runtime() {
  if (instance_ != XR_NULL_HANDLE) xrDestroyInstance(instance_);
}

VkInstance Runtime::createInstance(const VkInstanceCreateInfo& create) {
  auto info = xrStruct<XrVulkanInstanceCreateInfoKHR>(XR_TYPE_VULKAN_INSTANCE_CREATE_INFO_KHR);
  info.systemId = system_;
  info.pfnGetInstanceProcAddr = &vkGetInstanceProcAddr;
  info.vulkanCreateInfo = &create;
  VkInstance instance = VK_NULL_HANDLE;
  VkResult vulkan = VK_SUCCESS;
  check(instanceFunction<PFN_xrCreateVulkanInstanceKHR>(instance_, "xrCreateVulkanInstanceKHR")(instance_, &info,
                                                                                                &instance, &vulkan),
        name_ + " making the Vulkan instance (xrCreateVulkanInstanceKHR)");
  gpu::check(vulkan, "vkCreateInstance through " + name_);
  return instance;
}

VkPhysicalDevice Runtime::physicalDevice(VkInstance instance) {
  auto info = xrStruct<XrVulkanGraphicsDeviceGetInfoKHR>(XR_TYPE_VULKAN_GRAPHICS_DEVICE_GET_INFO_KHR);
  info.systemId = system_;
  info.vulkanInstance = instance;
  VkPhysicalDevice physical = VK_NULL_HANDLE;
  check(instanceFunction<PFN_xrGetVulkanGraphicsDevice2KHR>(instance_, "xrGetVulkanGraphicsDevice2KHR")(
            instance_, &info, &physical),
        name_ + " naming the headset's GPU (xrGetVulkanGraphicsDevice2KHR)");
  return physical;
}

VkDevice Runtime::createDevice(VkPhysicalDevice physical, const VkDeviceCreateInfo& create) {
  auto info = xrStruct<XrVulkanDeviceCreateInfoKHR>(XR_TYPE_VULKAN_DEVICE_CREATE_INFO_KHR);
  info.systemId = system_;
  info.pfnGetInstanceProcAddr = &vkGetInstanceProcAddr;
  info.vulkanPhysicalDevice = physical;
  info.vulkanCreateInfo = &create;
  VkDevice device = VK_NULL_HANDLE;
  VkResult vulkan = VK_SUCCESS;
  check(instanceFunction<PFN_xrCreateVulkanDeviceKHR>(instance_, "xrCreateVulkanDeviceKHR")(instance_, &info, &device,
                                                                                            &vulkan),
        name_ + " making the Vulkan device (xrCreateVulkanDeviceKHR)");
  gpu::check(vulkan, "vkCreateDevice through " + name_);
  return device;
}

}  // namespace plumb::xr
