#pragma once
// A timeline semaphore (Vulkan 1.2 core): one 64-bit counter that submissions signal and the
// host or other submissions wait for. The renderer signals the frame number on it; the frame
// pacing and the deletion queue read it.

#include <vulkan/vulkan.h>

#include <cstdint>

namespace plumb::gpu {

class Device;

class TimelineSemaphore {
 public:
  explicit TimelineSemaphore(const Device& device, std::uint64_t initial_value = 0);
  ~TimelineSemaphore();
  TimelineSemaphore(const TimelineSemaphore&) = delete;
  TimelineSemaphore& operator=(const TimelineSemaphore&) = delete;

  VkSemaphore handle() const { return semaphore_; }
  std::uint64_t value() const;
  // Whether the counter reached `value` within `timeout_ns`; throws on device loss.
  bool wait(std::uint64_t value, std::uint64_t timeout_ns) const;
  void signalFromHost(std::uint64_t value);

 private:
  VkDevice device_;
  VkSemaphore semaphore_ = VK_NULL_HANDLE;
};

}  // namespace plumb::gpu
