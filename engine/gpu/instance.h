#pragma once
// The Vulkan instance, with the Khronos validation layer and a debug messenger when asked (tests
// and debug builds): every validation message is kept, so that a test can fail on any of them.

#include <vulkan/vulkan.h>

#include <mutex>
#include <string>
#include <vector>

namespace plumb::gpu {

class VulkanFactory;

struct InstanceOptions {
  bool validation = false;           // the layer must be installed (vulkan-validationlayers)
  VulkanFactory* factory = nullptr;  // makes the instance (a headset's runtime); null: vkCreateInstance
};

// What the commands and the app use: validation in debug builds where the layer is installed;
// the environment variable PLUMB_VALIDATION=1 or 0 forces it on or off.
InstanceOptions instanceOptionsFromEnvironment();

class Instance {
 public:
  // `extensions`: instance extensions besides validation's, e.g. what the window system needs
  // for surfaces (glfwGetRequiredInstanceExtensions).
  explicit Instance(const InstanceOptions& options = {}, const std::vector<const char*>& extensions = {});
  ~Instance();
  Instance(const Instance&) = delete;
  Instance& operator=(const Instance&) = delete;

  VkInstance handle() const { return instance_; }
  bool validating() const { return messenger_ != VK_NULL_HANDLE; }

  // The validation layer's warnings and errors so far, oldest first ("[error] VUID-...: text").
  std::vector<std::string> validationMessages() const;

 private:
  static VKAPI_ATTR VkBool32 VKAPI_CALL onMessage(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                                  VkDebugUtilsMessageTypeFlagsEXT types,
                                                  const VkDebugUtilsMessengerCallbackDataEXT* data, void* self);

  VkInstance instance_ = VK_NULL_HANDLE;
  VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
  mutable std::mutex mutex_;  // the layer may call from any thread
  std::vector<std::string> messages_;
};

}  // namespace plumb::gpu
