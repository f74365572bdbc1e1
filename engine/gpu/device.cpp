// Device selection and creation.
//
//   1. Every physical device is checked for Vulkan 1.3, a queue family with graphics and
//      compute, and the features the renderer needs; what a device lacks is remembered.
//   2. Of the suitable ones, the forced choice (DeviceChoice, PLUMB_GPU) or the best type:
//      discrete, integrated, virtual, CPU.
//   3. The logical device enables exactly the needed features, with one queue.

#include "engine/gpu/device.h"

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <optional>
#include <vector>

#include "engine/gpu/instance.h"
#include "engine/gpu/vk_check.h"
#include "engine/gpu/vulkan_factory.h"

namespace plumb::gpu {
namespace {

int typeRank(VkPhysicalDeviceType type) {
  switch (type) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU:
      return 0;
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU:
      return 1;
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU:
      return 2;
    case VK_PHYSICAL_DEVICE_TYPE_CPU:
      return 3;
    default:
      return 4;
  }
}

// The feature structures that hold what the renderer needs, linked as Vulkan expects: queried
// to judge a device, then filled to enable exactly those features.
struct FeatureChain {
  VkPhysicalDeviceVulkan13Features v13{};
  VkPhysicalDeviceVulkan12Features v12{};
  VkPhysicalDeviceFeatures2 base{};

  FeatureChain() {
    v13.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES;
    v12.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES;
    v12.pNext = &v13;
    base.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2;
    base.pNext = &v12;
  }
  FeatureChain(const FeatureChain&) = delete;  // the chain points into itself
  FeatureChain& operator=(const FeatureChain&) = delete;

  // Calls visit(flag, name) for each feature the renderer needs.
  template <typename Visit>
  void forEachNeeded(Visit&& visit) {
    visit(base.features.shaderInt64, "shaderInt64");
    visit(v12.shaderBufferInt64Atomics, "shaderBufferInt64Atomics");
    visit(v12.bufferDeviceAddress, "bufferDeviceAddress");
    visit(v12.timelineSemaphore, "timelineSemaphore");
    visit(v13.synchronization2, "synchronization2");
    visit(v13.maintenance4, "maintenance4");          // glslc's SPIR-V for Vulkan 1.3 sets workgroup sizes by id
    visit(v13.dynamicRendering, "dynamicRendering");  // the overlay pass renders without render passes
  }
};

struct Candidate {
  VkPhysicalDevice device = VK_NULL_HANDLE;
  VkPhysicalDeviceProperties properties{};
  std::uint32_t queue_family = 0;
};

bool hasExtension(VkPhysicalDevice device, const char* name) {
  std::uint32_t count = 0;
  check(vkEnumerateDeviceExtensionProperties(device, nullptr, &count, nullptr), "vkEnumerateDeviceExtensionProperties");
  std::vector<VkExtensionProperties> extensions(count);
  check(vkEnumerateDeviceExtensionProperties(device, nullptr, &count, extensions.data()),
        "vkEnumerateDeviceExtensionProperties", VK_INCOMPLETE);
  return std::any_of(extensions.begin(), extensions.end(),
                     [&](const VkExtensionProperties& e) { return std::strcmp(e.extensionName, name) == 0; });
}

// Why `device` cannot serve (empty when it can); fills the queue family.
std::string unsuitable(VkPhysicalDevice device, VkSurfaceKHR surface, Candidate& candidate) {
  vkGetPhysicalDeviceProperties(device, &candidate.properties);
  if (candidate.properties.apiVersion < VK_API_VERSION_1_3) return "Vulkan 1.3";
  std::uint32_t count = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(device, &count, nullptr);
  std::vector<VkQueueFamilyProperties> families(count);
  vkGetPhysicalDeviceQueueFamilyProperties(device, &count, families.data());
  std::optional<std::uint32_t> family;
  for (std::uint32_t i = 0; i < count && !family; ++i) {
    const VkQueueFlags wanted = VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT;
    VkBool32 presents = VK_TRUE;
    if (surface != VK_NULL_HANDLE) {
      check(vkGetPhysicalDeviceSurfaceSupportKHR(device, i, surface, &presents),
            "vkGetPhysicalDeviceSurfaceSupportKHR");
    }
    if ((families[i].queueFlags & wanted) == wanted && presents) family = i;
  }
  if (!family)
    return surface != VK_NULL_HANDLE ? "a graphics and compute queue that presents to the window"
                                     : "a graphics and compute queue";
  if (surface != VK_NULL_HANDLE && !hasExtension(device, VK_KHR_SWAPCHAIN_EXTENSION_NAME))
    return VK_KHR_SWAPCHAIN_EXTENSION_NAME;
  candidate.queue_family = *family;

  FeatureChain available;
  vkGetPhysicalDeviceFeatures2(device, &available.base);
  std::string missing;
  available.forEachNeeded([&](const VkBool32& present, const char* name) {
    if (!present) missing += (missing.empty() ? "" : ", ") + std::string(name);
  });
  return missing;
}

bool matches(const DeviceChoice& choice, const VkPhysicalDeviceProperties& properties) {
  if (choice.prefer.empty()) return true;
  if (choice.prefer == "discrete") return properties.deviceType == VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU;
  if (choice.prefer == "cpu") return properties.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU;
  return std::string(properties.deviceName).find(choice.prefer) != std::string::npos;
}

}  // namespace

DeviceChoice deviceChoiceFromEnvironment() {
  const char* value = std::getenv("PLUMB_GPU");
  return {value ? value : ""};
}

Device::Device(const Instance& instance, const DeviceChoice& choice) {
  std::uint32_t count = 0;
  check(vkEnumeratePhysicalDevices(instance.handle(), &count, nullptr), "vkEnumeratePhysicalDevices");
  std::vector<VkPhysicalDevice> devices(count);
  check(vkEnumeratePhysicalDevices(instance.handle(), &count, devices.data()), "vkEnumeratePhysicalDevices",
        VK_INCOMPLETE);

  if (choice.factory != nullptr) devices = {choice.factory->physicalDevice(instance.handle())};

  std::optional<Candidate> best;
  std::string rejected;
  for (VkPhysicalDevice device : devices) {
    Candidate candidate;
    candidate.device = device;
    const std::string lacks = unsuitable(device, choice.present_to, candidate);
    const std::string name = candidate.properties.deviceName;
    if (!lacks.empty()) {
      rejected += "; " + name + " lacks " + lacks;
    } else if (choice.factory == nullptr && !matches(choice, candidate.properties)) {
      rejected += "; " + name + " is not '" + choice.prefer + "'";
    } else if (!best || typeRank(candidate.properties.deviceType) < typeRank(best->properties.deviceType)) {
      best = candidate;
    }
  }
  if (!best) {
    if (choice.factory != nullptr) {
      throw Error("the headset's GPU cannot run Plumb" + rejected);
    }
    throw Error("no Vulkan device can run Plumb" + (devices.empty() ? std::string(": none found") : rejected) +
                " (install 'mesa-vulkan-drivers' for lavapipe on the CPU; PLUMB_GPU chooses a device)");
  }
  physical_ = best->device;
  properties_ = best->properties;
  queue_family_ = best->queue_family;
  vkGetPhysicalDeviceMemoryProperties(physical_, &memory_);

  FeatureChain enabled;
  enabled.forEachNeeded([](VkBool32& flag, const char*) { flag = VK_TRUE; });

  const float priority = 1.0f;
  VkDeviceQueueCreateInfo queue{};
  queue.sType = VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO;
  queue.queueFamilyIndex = queue_family_;
  queue.queueCount = 1;
  queue.pQueuePriorities = &priority;
  const char* const swapchain_extension = VK_KHR_SWAPCHAIN_EXTENSION_NAME;
  VkDeviceCreateInfo create{};
  create.sType = VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO;
  create.pNext = &enabled.base;
  create.queueCreateInfoCount = 1;
  create.pQueueCreateInfos = &queue;
  if (choice.present_to != VK_NULL_HANDLE) {
    create.enabledExtensionCount = 1;
    create.ppEnabledExtensionNames = &swapchain_extension;
  }
  if (choice.factory != nullptr) {
    device_ = choice.factory->createDevice(physical_, create);
  } else {
    check(vkCreateDevice(physical_, &create, nullptr, &device_), "vkCreateDevice");
  }
  vkGetDeviceQueue(device_, queue_family_, 0, &queue_);
  if (instance.validating()) {
    set_object_name_ = reinterpret_cast<PFN_vkSetDebugUtilsObjectNameEXT>(
        vkGetInstanceProcAddr(instance.handle(), "vkSetDebugUtilsObjectNameEXT"));
  }
}

void Device::setName(VkObjectType type, std::uint64_t handle, const char* name) const {
  if (set_object_name_ == nullptr || handle == 0) return;
  VkDebugUtilsObjectNameInfoEXT info{};
  info.sType = VK_STRUCTURE_TYPE_DEBUG_UTILS_OBJECT_NAME_INFO_EXT;
  info.objectType = type;
  info.objectHandle = handle;
  info.pObjectName = name;
  check(set_object_name_(device_, &info), "vkSetDebugUtilsObjectNameEXT");
}

Device::~Device() {
  if (device_ != VK_NULL_HANDLE) {
    vkDeviceWaitIdle(device_);  // nothing may be in flight when the device goes
    vkDestroyDevice(device_, nullptr);
  }
}

std::uint32_t Device::memoryType(std::uint32_t type_bits, VkMemoryPropertyFlags required) const {
  for (std::uint32_t i = 0; i < memory_.memoryTypeCount; ++i) {
    if ((type_bits & (1u << i)) && (memory_.memoryTypes[i].propertyFlags & required) == required) return i;
  }
  throw Error("the Vulkan device " + name() + " has no memory type with the properties needed");
}

}  // namespace plumb::gpu
