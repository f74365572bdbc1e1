#pragma once
// Every VkResult is checked: a failure becomes a plumb::Error naming the call and the result;
// a lost device is its own type, so that the app can report it and start over instead of dying.

#include <vulkan/vulkan.h>

#include <string_view>

#include "engine/core/error.h"

namespace plumb::gpu {

class DeviceLost : public Error {
 public:
  using Error::Error;
};

// "VK_ERROR_OUT_OF_DEVICE_MEMORY" and so on; the number for results this build does not know.
std::string resultName(VkResult result);

// Throws unless `result` is VK_SUCCESS (or, where `also_fine` says so, that value too).
void check(VkResult result, std::string_view call, VkResult also_fine = VK_SUCCESS);

}  // namespace plumb::gpu
