// Instance creation, paper-independent plumbing.
//
//   1. Vulkan 1.3 (the renderer relies on timeline semaphores, synchronization2 and 64-bit
//      atomics, all core or promoted there).
//   2. With validation: the layer, VK_EXT_debug_utils, and a messenger for warnings and errors
//      that records them; a missing layer is an error that names the Debian package.

#include "engine/gpu/instance.h"

#include <dlfcn.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>

#include "engine/gpu/vk_check.h"
#include "engine/gpu/vulkan_factory.h"

namespace plumb::gpu {
namespace {

constexpr const char* kValidationLayer = "VK_LAYER_KHRONOS_validation";

bool layerAvailable(const char* name) {
  std::uint32_t count = 0;
  check(vkEnumerateInstanceLayerProperties(&count, nullptr), "vkEnumerateInstanceLayerProperties");
  std::vector<VkLayerProperties> layers(count);
  check(vkEnumerateInstanceLayerProperties(&count, layers.data()), "vkEnumerateInstanceLayerProperties", VK_INCOMPLETE);
  return std::any_of(layers.begin(), layers.end(),
                     [&](const VkLayerProperties& layer) { return std::strcmp(layer.layerName, name) == 0; });
}

// Keeps Mesa's lavapipe mapped until the process ends. Lavapipe allocates a small block in a
// one-time initialisation and keeps it in a global; when the Vulkan loader unloads the driver at
// vkDestroyInstance, LeakSanitizer finds the block unreferenced in an unknown module and fails
// the run, although nothing leaks per instance. With the library kept (RTLD_NODELETE) the global
// still points at the block. Harmless elsewhere: a machine without lavapipe loads nothing.
void keepCpuDriverLoaded() {
  static void* const kept = dlopen("libvulkan_lvp.so", RTLD_NOW | RTLD_NODELETE);
  (void)kept;
}

}  // namespace

InstanceOptions instanceOptionsFromEnvironment() {
  const char* forced = std::getenv("PLUMB_VALIDATION");
  if (forced != nullptr && *forced != '\0') return {.validation = std::strcmp(forced, "0") != 0};
#ifdef NDEBUG
  return {.validation = false};
#else
  return {.validation = layerAvailable(kValidationLayer)};
#endif
}

Instance::Instance(const InstanceOptions& options, const std::vector<const char*>& extra_extensions) {
  keepCpuDriverLoaded();
  VkApplicationInfo application{};
  application.sType = VK_STRUCTURE_TYPE_APPLICATION_INFO;
  application.pApplicationName = "Plumb";
  application.pEngineName = "Plumb";
  application.apiVersion = VK_API_VERSION_1_3;

  std::vector<const char*> layers, extensions;
  VkDebugUtilsMessengerCreateInfoEXT messenger{};
  messenger.sType = VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT;
  messenger.messageSeverity =
      VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
  messenger.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                          VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
  messenger.pfnUserCallback = &Instance::onMessage;
  messenger.pUserData = this;
  if (options.validation) {
    if (!layerAvailable(kValidationLayer)) {
      throw Error(std::string("the Vulkan validation layer ") + kValidationLayer +
                  " is not installed: install the Debian package 'vulkan-validationlayers' (scripts/setup does)");
    }
    layers.push_back(kValidationLayer);
    extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
  }

  extensions.insert(extensions.end(), extra_extensions.begin(), extra_extensions.end());

  VkInstanceCreateInfo create{};
  create.sType = VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO;
  create.pNext = options.validation ? &messenger : nullptr;  // also reports on create and destroy
  create.pApplicationInfo = &application;
  create.enabledLayerCount = static_cast<std::uint32_t>(layers.size());
  create.ppEnabledLayerNames = layers.data();
  create.enabledExtensionCount = static_cast<std::uint32_t>(extensions.size());
  create.ppEnabledExtensionNames = extensions.data();
  if (options.factory != nullptr) {
    instance_ = options.factory->createInstance(create);
  } else {
    const VkResult result = vkCreateInstance(&create, nullptr, &instance_);
    if (result == VK_ERROR_INCOMPATIBLE_DRIVER) {
      throw Error("no Vulkan 1.3 driver: install the Debian package 'mesa-vulkan-drivers' for lavapipe on the CPU");
    }
    check(result, "vkCreateInstance");
  }

  if (options.validation) {
    const auto create_messenger = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(instance_, "vkCreateDebugUtilsMessengerEXT"));
    const VkResult made = create_messenger ? create_messenger(instance_, &messenger, nullptr, &messenger_)
                                           : VK_ERROR_EXTENSION_NOT_PRESENT;
    if (made != VK_SUCCESS) {
      vkDestroyInstance(instance_, nullptr);
      check(made, "vkCreateDebugUtilsMessengerEXT");
    }
  }
}

Instance::~Instance() {
  if (messenger_ != VK_NULL_HANDLE) {
    const auto destroy_messenger = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(instance_, "vkDestroyDebugUtilsMessengerEXT"));
    if (destroy_messenger) destroy_messenger(instance_, messenger_, nullptr);
  }
  vkDestroyInstance(instance_, nullptr);
}

std::vector<std::string> Instance::validationMessages() const {
  const std::lock_guard lock(mutex_);
  return messages_;
}

VKAPI_ATTR VkBool32 VKAPI_CALL Instance::onMessage(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                                   VkDebugUtilsMessageTypeFlagsEXT /*types*/,
                                                   const VkDebugUtilsMessengerCallbackDataEXT* data, void* self) {
  auto* instance = static_cast<Instance*>(self);
  const char* level = (severity & VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT) ? "error" : "warning";
  std::string message = std::string("[") + level + "] " + (data->pMessageIdName ? data->pMessageIdName : "") + ": " +
                        (data->pMessage ? data->pMessage : "");
  const std::lock_guard lock(instance->mutex_);
  instance->messages_.push_back(std::move(message));
  return VK_FALSE;  // never abort the call: the test decides
}

}  // namespace plumb::gpu
