#pragma once
// Command recording and submission. A CommandPool owns the command buffers of one thread and
// one frame slot; reset() recycles them all at once, which is how frames reuse theirs once the
// timeline says the GPU is done with them. submit() signals a timeline value when the work ends:
// that value is what the deletion queue and the frame pacing wait for.

#include <vulkan/vulkan.h>

#include <cstdint>
#include <vector>

namespace plumb::gpu {

class Device;
class TimelineSemaphore;

class CommandPool {
 public:
  CommandPool(const Device& device, const char* name);
  ~CommandPool();
  CommandPool(const CommandPool&) = delete;
  CommandPool& operator=(const CommandPool&) = delete;

  // A primary command buffer in the recording state (one-time submit). Owned by the pool.
  VkCommandBuffer begin();
  // Every buffer begun since the last reset returns to the pool; none may be in flight.
  void reset();

 private:
  const Device& device_;
  VkCommandPool pool_ = VK_NULL_HANDLE;
  std::vector<VkCommandBuffer> buffers_;  // allocated so far, reused after reset
  std::size_t in_use_ = 0;
};

struct TimelineWait {
  const TimelineSemaphore* semaphore;
  std::uint64_t value;
  VkPipelineStageFlags2 stages;
};

// Ends `commands` and submits it to the device's queue, to signal `signal_value` on `timeline`
// when done, after the optional binary semaphore `wait_binary` (a swapchain image) at `wait_stages`.
// `signal_binary` (the swapchain's present wait), when not null, is signalled too.
void submit(const Device& device, VkCommandBuffer commands, const TimelineSemaphore& timeline,
            std::uint64_t signal_value, VkSemaphore wait_binary = VK_NULL_HANDLE,
            VkPipelineStageFlags2 wait_stages = VK_PIPELINE_STAGE_2_NONE, VkSemaphore signal_binary = VK_NULL_HANDLE);

// A memory barrier between two passes of one command buffer (synchronization2).
void memoryBarrier(VkCommandBuffer commands, VkPipelineStageFlags2 src_stages, VkAccessFlags2 src_access,
                   VkPipelineStageFlags2 dst_stages, VkAccessFlags2 dst_access);

// Moves `image` (the whole colour image) from one layout to another, after `src` and before `dst`.
void imageBarrier(VkCommandBuffer commands, VkImage image, VkImageLayout from, VkImageLayout to,
                  VkPipelineStageFlags2 src_stages, VkAccessFlags2 src_access, VkPipelineStageFlags2 dst_stages,
                  VkAccessFlags2 dst_access, VkImageAspectFlags aspect = VK_IMAGE_ASPECT_COLOR_BIT);

}  // namespace plumb::gpu
