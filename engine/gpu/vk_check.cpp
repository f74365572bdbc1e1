#include "engine/gpu/vk_check.h"

#include <string>

namespace plumb::gpu {

std::string resultName(VkResult result) {
  switch (result) {
#define PLUMB_RESULT(name) \
  case name:               \
    return #name;
    PLUMB_RESULT(VK_SUCCESS)
    PLUMB_RESULT(VK_NOT_READY)
    PLUMB_RESULT(VK_TIMEOUT)
    PLUMB_RESULT(VK_INCOMPLETE)
    PLUMB_RESULT(VK_SUBOPTIMAL_KHR)
    PLUMB_RESULT(VK_ERROR_OUT_OF_HOST_MEMORY)
    PLUMB_RESULT(VK_ERROR_OUT_OF_DEVICE_MEMORY)
    PLUMB_RESULT(VK_ERROR_INITIALIZATION_FAILED)
    PLUMB_RESULT(VK_ERROR_DEVICE_LOST)
    PLUMB_RESULT(VK_ERROR_MEMORY_MAP_FAILED)
    PLUMB_RESULT(VK_ERROR_LAYER_NOT_PRESENT)
    PLUMB_RESULT(VK_ERROR_EXTENSION_NOT_PRESENT)
    PLUMB_RESULT(VK_ERROR_FEATURE_NOT_PRESENT)
    PLUMB_RESULT(VK_ERROR_INCOMPATIBLE_DRIVER)
    PLUMB_RESULT(VK_ERROR_TOO_MANY_OBJECTS)
    PLUMB_RESULT(VK_ERROR_FORMAT_NOT_SUPPORTED)
    PLUMB_RESULT(VK_ERROR_OUT_OF_DATE_KHR)
    PLUMB_RESULT(VK_ERROR_SURFACE_LOST_KHR)
#undef PLUMB_RESULT
    default:
      return "VkResult " + std::to_string(static_cast<int>(result));
  }
}

void check(VkResult result, std::string_view call, VkResult also_fine) {
  if (result == VK_SUCCESS || result == also_fine) return;
  const std::string message = std::string(call) + " failed: " + resultName(result);
  if (result == VK_ERROR_DEVICE_LOST) throw DeviceLost(message + " (the GPU driver reset or crashed)");
  throw Error(message);
}

}  // namespace plumb::gpu
