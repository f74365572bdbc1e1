#pragma once
// The physical device Plumb runs on and its logical device with one queue for graphics and
// compute. A discrete GPU is preferred, then an integrated or virtual one, then the CPU
// (Mesa's lavapipe); `DeviceChoice` or the environment variable PLUMB_GPU forces one:
// "discrete", "cpu", or a part of the device's name ("llvmpipe", "RTX").
//
// The renderer needs, and the device enables: 64-bit integers and 64-bit buffer atomics (the
// splat's atomicMin of depth << 32 | point id), buffer device address, timeline semaphores
// (frame pacing), synchronization2, dynamic rendering (overlays) and maintenance4 (which the SPIR-V
// of shaders/ needs). A device without them is
// passed over, and if none is left the error lists what each lacked.

#include <vulkan/vulkan.h>

#include <cstdint>
#include <string>

namespace plumb::gpu {

class Instance;
class VulkanFactory;

struct DeviceChoice {
  // Empty: automatic (discrete first). "discrete", "cpu", or a part of the device name.
  std::string prefer;
  // A window's surface the device must present to (its queue family, VK_KHR_swapchain);
  // VK_NULL_HANDLE for headless work.
  VkSurfaceKHR present_to = VK_NULL_HANDLE;
  // A headset's runtime: it names the one physical device to use (`prefer` is then ignored) and
  // makes the logical device. Null: Plumb chooses and vkCreateDevice makes it.
  VulkanFactory* factory = nullptr;
};

// The choice PLUMB_GPU asks for (automatic when unset).
DeviceChoice deviceChoiceFromEnvironment();

class Device {
 public:
  Device(const Instance& instance, const DeviceChoice& choice);
  ~Device();
  Device(const Device&) = delete;
  Device& operator=(const Device&) = delete;

  VkPhysicalDevice physical() const { return physical_; }
  VkDevice handle() const { return device_; }
  VkQueue queue() const { return queue_; }
  std::uint32_t queueFamily() const { return queue_family_; }
  const VkPhysicalDeviceProperties& properties() const { return properties_; }
  std::string name() const { return properties_.deviceName; }
  bool isCpu() const { return properties_.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU; }

  // A memory type index with all of `required` among the bits of `type_bits`; throws if none.
  std::uint32_t memoryType(std::uint32_t type_bits, VkMemoryPropertyFlags required) const;
  VkMemoryPropertyFlags memoryTypeFlags(std::uint32_t type) const { return memory_.memoryTypes[type].propertyFlags; }

  // Names `handle` for the validation layer's messages and debuggers; does nothing unless the
  // instance validates (VK_EXT_debug_utils is on only then).
  void setName(VkObjectType type, std::uint64_t handle, const char* name) const;
  template <typename Handle>
  void setName(VkObjectType type, Handle handle, const char* name) const {
    setName(type, reinterpret_cast<std::uint64_t>(handle), name);
  }

 private:
  VkPhysicalDevice physical_ = VK_NULL_HANDLE;
  VkDevice device_ = VK_NULL_HANDLE;
  VkQueue queue_ = VK_NULL_HANDLE;
  std::uint32_t queue_family_ = 0;
  VkPhysicalDeviceProperties properties_{};
  VkPhysicalDeviceMemoryProperties memory_{};
  PFN_vkSetDebugUtilsObjectNameEXT set_object_name_ = nullptr;
};

}  // namespace plumb::gpu
