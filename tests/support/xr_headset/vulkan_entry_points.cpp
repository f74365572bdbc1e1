// XR_KHR_vulkan_enable2's entry points (OpenXR 1.0 specification, chapter 12, section
// "XR_KHR_vulkan_enable2"): the Vulkan versions the runtime accepts, and the Vulkan instance and
// device made for the application through its own vkGetInstanceProcAddr with its create infos
// unchanged (a real runtime may add extensions it needs; this one needs none). The physical device
// is chosen here, and later calls must use that one:
//   1. the one whose name contains PLUMB_XR_HEADSET_GPU, when set;
//   2. else the first CPU device (Mesa's lavapipe), so tests do not depend on the machine's card;
//   3. else the first.

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <string>
#include <vector>

#include "tests/support/xr_headset/entry_points.h"
#include "tests/support/xr_headset/runtime_state.h"

namespace plumb::xr_headset {
namespace {

std::string lowerCase(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(),
                 [](char c) { return static_cast<char>(std::tolower(static_cast<unsigned char>(c))); });
  return text;
}

// The instance, checked, with the extension enabled and the system id ours.
XrResult checkInstance(const char* function, XrInstance instance, XrSystemId system_id, Instance*& found) {
  found = find(runtime().instances, idOf(instance));
  if (found == nullptr) return misuse(XR_ERROR_HANDLE_INVALID, function, "unknown XrInstance");
  if (!found->vulkan_enable2) {
    return misuse(XR_ERROR_FUNCTION_UNSUPPORTED, function, "the instance did not enable XR_KHR_vulkan_enable2");
  }
  if (system_id != kSystemId) return misuse(XR_ERROR_SYSTEM_INVALID, function, "unknown XrSystemId");
  return XR_SUCCESS;
}

XrResult choosePhysicalDevice(const char* function, VkInstance vulkan_instance, VkPhysicalDevice& chosen) {
  std::uint32_t count = 0;
  if (!vulkanSucceeded(vkEnumeratePhysicalDevices(vulkan_instance, &count, nullptr), "vkEnumeratePhysicalDevices")) {
    return XR_ERROR_RUNTIME_FAILURE;
  }
  std::vector<VkPhysicalDevice> devices(count);
  if (!vulkanSucceeded(vkEnumeratePhysicalDevices(vulkan_instance, &count, devices.data()),
                       "vkEnumeratePhysicalDevices")) {
    return XR_ERROR_RUNTIME_FAILURE;
  }
  if (devices.empty()) return misuse(XR_ERROR_RUNTIME_FAILURE, function, "the Vulkan instance has no devices");
  const char* wanted = std::getenv("PLUMB_XR_HEADSET_GPU");
  std::string names;
  for (VkPhysicalDevice device : devices) {
    VkPhysicalDeviceProperties properties{};
    vkGetPhysicalDeviceProperties(device, &properties);
    names += std::string(names.empty() ? "" : ", ") + properties.deviceName;
    if (wanted != nullptr && *wanted != '\0') {
      if (lowerCase(properties.deviceName).find(lowerCase(wanted)) != std::string::npos) {
        chosen = device;
        return XR_SUCCESS;
      }
    } else if (properties.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU) {
      chosen = device;
      return XR_SUCCESS;
    }
  }
  if (wanted != nullptr && *wanted != '\0') {
    return misuse(XR_ERROR_RUNTIME_FAILURE, function,
                  std::string("PLUMB_XR_HEADSET_GPU=") + wanted + " names none of the devices (" + names + ")");
  }
  chosen = devices.front();
  return XR_SUCCESS;
}

}  // namespace

XrResult XRAPI_CALL xrGetVulkanGraphicsRequirements2KHR(XrInstance instance, XrSystemId system_id,
                                                        XrGraphicsRequirementsVulkanKHR* requirements) {
  constexpr const char* kSelf = "xrGetVulkanGraphicsRequirements2KHR";
  std::lock_guard lock(runtime().mutex);
  Instance* owner = nullptr;
  if (const XrResult checked = checkInstance(kSelf, instance, system_id, owner); XR_FAILED(checked)) return checked;
  if (requirements == nullptr || requirements->type != XR_TYPE_GRAPHICS_REQUIREMENTS_VULKAN2_KHR) {
    return misuse(XR_ERROR_VALIDATION_FAILURE, kSelf,
                  "graphicsRequirements must have type XR_TYPE_GRAPHICS_REQUIREMENTS_VULKAN2_KHR");
  }
  requirements->minApiVersionSupported = XR_MAKE_VERSION(1, 0, 0);
  requirements->maxApiVersionSupported = XR_MAKE_VERSION(1, 3, 0);
  owner->graphics_requirements_queried = true;
  return XR_SUCCESS;
}

XrResult XRAPI_CALL xrCreateVulkanInstanceKHR(XrInstance instance, const XrVulkanInstanceCreateInfoKHR* create_info,
                                              VkInstance* vulkan_instance, VkResult* vulkan_result) {
  constexpr const char* kSelf = "xrCreateVulkanInstanceKHR";
  std::lock_guard lock(runtime().mutex);
  if (create_info == nullptr || vulkan_instance == nullptr || vulkan_result == nullptr) {
    return misuse(XR_ERROR_VALIDATION_FAILURE, kSelf, "a null argument");
  }
  Instance* owner = nullptr;
  if (const XrResult checked = checkInstance(kSelf, instance, create_info->systemId, owner); XR_FAILED(checked)) {
    return checked;
  }
  if (create_info->type != XR_TYPE_VULKAN_INSTANCE_CREATE_INFO_KHR || create_info->createFlags != 0 ||
      create_info->pfnGetInstanceProcAddr == nullptr || create_info->vulkanCreateInfo == nullptr) {
    return misuse(XR_ERROR_VALIDATION_FAILURE, kSelf,
                  "createInfo needs type XR_TYPE_VULKAN_INSTANCE_CREATE_INFO_KHR, createFlags 0, "
                  "pfnGetInstanceProcAddr and vulkanCreateInfo");
  }
  const auto create =
      reinterpret_cast<PFN_vkCreateInstance>(create_info->pfnGetInstanceProcAddr(VK_NULL_HANDLE, "vkCreateInstance"));
  if (create == nullptr)
    return misuse(XR_ERROR_RUNTIME_FAILURE, kSelf, "pfnGetInstanceProcAddr has no vkCreateInstance");
  // The Vulkan outcome travels in vulkanResult; the call itself did what it was asked.
  *vulkan_result = create(create_info->vulkanCreateInfo, create_info->vulkanAllocator, vulkan_instance);
  vulkanSucceeded(*vulkan_result, "vkCreateInstance");
  return XR_SUCCESS;
}

XrResult XRAPI_CALL xrGetVulkanGraphicsDevice2KHR(XrInstance instance, const XrVulkanGraphicsDeviceGetInfoKHR* get_info,
                                                  VkPhysicalDevice* physical_device) {
  constexpr const char* kSelf = "xrGetVulkanGraphicsDevice2KHR";
  std::lock_guard lock(runtime().mutex);
  if (get_info == nullptr || physical_device == nullptr)
    return misuse(XR_ERROR_VALIDATION_FAILURE, kSelf, "a null argument");
  Instance* owner = nullptr;
  if (const XrResult checked = checkInstance(kSelf, instance, get_info->systemId, owner); XR_FAILED(checked)) {
    return checked;
  }
  if (get_info->type != XR_TYPE_VULKAN_GRAPHICS_DEVICE_GET_INFO_KHR || get_info->vulkanInstance == VK_NULL_HANDLE) {
    return misuse(XR_ERROR_VALIDATION_FAILURE, kSelf,
                  "getInfo needs type XR_TYPE_VULKAN_GRAPHICS_DEVICE_GET_INFO_KHR and a vulkanInstance");
  }
  VkPhysicalDevice chosen = VK_NULL_HANDLE;
  if (const XrResult result = choosePhysicalDevice(kSelf, get_info->vulkanInstance, chosen); XR_FAILED(result)) {
    return result;
  }
  owner->vulkan_instance = get_info->vulkanInstance;
  owner->physical_device = chosen;
  *physical_device = chosen;
  return XR_SUCCESS;
}

XrResult XRAPI_CALL xrCreateVulkanDeviceKHR(XrInstance instance, const XrVulkanDeviceCreateInfoKHR* create_info,
                                            VkDevice* vulkan_device, VkResult* vulkan_result) {
  constexpr const char* kSelf = "xrCreateVulkanDeviceKHR";
  std::lock_guard lock(runtime().mutex);
  if (create_info == nullptr || vulkan_device == nullptr || vulkan_result == nullptr) {
    return misuse(XR_ERROR_VALIDATION_FAILURE, kSelf, "a null argument");
  }
  Instance* owner = nullptr;
  if (const XrResult checked = checkInstance(kSelf, instance, create_info->systemId, owner); XR_FAILED(checked)) {
    return checked;
  }
  if (create_info->type != XR_TYPE_VULKAN_DEVICE_CREATE_INFO_KHR || create_info->createFlags != 0 ||
      create_info->pfnGetInstanceProcAddr == nullptr || create_info->vulkanCreateInfo == nullptr) {
    return misuse(XR_ERROR_VALIDATION_FAILURE, kSelf,
                  "createInfo needs type XR_TYPE_VULKAN_DEVICE_CREATE_INFO_KHR, createFlags 0, "
                  "pfnGetInstanceProcAddr and vulkanCreateInfo");
  }
  if (owner->physical_device == VK_NULL_HANDLE || create_info->vulkanPhysicalDevice != owner->physical_device) {
    return misuse(XR_ERROR_HANDLE_INVALID, kSelf,
                  "vulkanPhysicalDevice must be the one xrGetVulkanGraphicsDevice2KHR returned");
  }
  const auto create = reinterpret_cast<PFN_vkCreateDevice>(
      create_info->pfnGetInstanceProcAddr(owner->vulkan_instance, "vkCreateDevice"));
  if (create == nullptr) return misuse(XR_ERROR_RUNTIME_FAILURE, kSelf, "pfnGetInstanceProcAddr has no vkCreateDevice");
  *vulkan_result = create(create_info->vulkanPhysicalDevice, create_info->vulkanCreateInfo,
                          create_info->vulkanAllocator, vulkan_device);
  vulkanSucceeded(*vulkan_result, "vkCreateDevice");
  return XR_SUCCESS;
}

}  // namespace plumb::xr_headset
