#include "engine/gpu/timeline.h"

#include "engine/gpu/device.h"
#include "engine/gpu/vk_check.h"

namespace plumb::gpu {

TimelineSemaphore::TimelineSemaphore(const Device& device, std::uint64_t initial_value) : device_(device.handle()) {
  VkSemaphoreTypeCreateInfo type{};
  type.sType = VK_STRUCTURE_TYPE_SEMAPHORE_TYPE_CREATE_INFO;
  type.semaphoreType = VK_SEMAPHORE_TYPE_TIMELINE;
  type.initialValue = initial_value;
  VkSemaphoreCreateInfo create{};
  create.sType = VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO;
  create.pNext = &type;
  check(vkCreateSemaphore(device_, &create, nullptr, &semaphore_), "vkCreateSemaphore (timeline)");
}

TimelineSemaphore::~TimelineSemaphore() {
  vkDestroySemaphore(device_, semaphore_, nullptr);
}

std::uint64_t TimelineSemaphore::value() const {
  std::uint64_t value = 0;
  check(vkGetSemaphoreCounterValue(device_, semaphore_, &value), "vkGetSemaphoreCounterValue");
  return value;
}

bool TimelineSemaphore::wait(std::uint64_t value, std::uint64_t timeout_ns) const {
  VkSemaphoreWaitInfo info{};
  info.sType = VK_STRUCTURE_TYPE_SEMAPHORE_WAIT_INFO;
  info.semaphoreCount = 1;
  info.pSemaphores = &semaphore_;
  info.pValues = &value;
  const VkResult result = vkWaitSemaphores(device_, &info, timeout_ns);
  check(result, "vkWaitSemaphores", VK_TIMEOUT);
  return result == VK_SUCCESS;
}

void TimelineSemaphore::signalFromHost(std::uint64_t value) {
  VkSemaphoreSignalInfo info{};
  info.sType = VK_STRUCTURE_TYPE_SEMAPHORE_SIGNAL_INFO;
  info.semaphore = semaphore_;
  info.value = value;
  check(vkSignalSemaphore(device_, &info), "vkSignalSemaphore");
}

}  // namespace plumb::gpu
