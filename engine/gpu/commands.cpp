#include "engine/gpu/commands.h"

#include <string>

#include "engine/gpu/device.h"
#include "engine/gpu/timeline.h"
#include "engine/gpu/vk_check.h"

namespace plumb::gpu {

CommandPool::CommandPool(const Device& device, const char* name) : device_(device) {
  VkCommandPoolCreateInfo create{};
  create.sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO;
  create.flags = VK_COMMAND_POOL_CREATE_TRANSIENT_BIT;
  create.queueFamilyIndex = device.queueFamily();
  check(vkCreateCommandPool(device.handle(), &create, nullptr, &pool_), "vkCreateCommandPool");
  device.setName(VK_OBJECT_TYPE_COMMAND_POOL, pool_, name);
}

CommandPool::~CommandPool() {
  vkDestroyCommandPool(device_.handle(), pool_, nullptr);  // frees its command buffers
}

VkCommandBuffer CommandPool::begin() {
  if (in_use_ == buffers_.size()) {
    VkCommandBufferAllocateInfo allocate{};
    allocate.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO;
    allocate.commandPool = pool_;
    allocate.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    allocate.commandBufferCount = 1;
    VkCommandBuffer buffer = VK_NULL_HANDLE;
    check(vkAllocateCommandBuffers(device_.handle(), &allocate, &buffer), "vkAllocateCommandBuffers");
    buffers_.push_back(buffer);
  }
  VkCommandBuffer buffer = buffers_[in_use_++];
  VkCommandBufferBeginInfo begin{};
  begin.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO;
  begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  check(vkBeginCommandBuffer(buffer, &begin), "vkBeginCommandBuffer");
  return buffer;
}

void CommandPool::reset() {
  check(vkResetCommandPool(device_.handle(), pool_, 0), "vkResetCommandPool");
  in_use_ = 0;
}

void submit(const Device& device, VkCommandBuffer commands, const TimelineSemaphore& timeline,
            std::uint64_t signal_value, VkSemaphore wait_binary, VkPipelineStageFlags2 wait_stages,
            VkSemaphore signal_binary) {
  check(vkEndCommandBuffer(commands), "vkEndCommandBuffer");
  VkCommandBufferSubmitInfo command_info{};
  command_info.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO;
  command_info.commandBuffer = commands;

  VkSemaphoreSubmitInfo wait{};
  wait.sType = VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO;
  wait.semaphore = wait_binary;
  wait.stageMask = wait_stages;

  VkSemaphoreSubmitInfo signals[2]{};
  signals[0].sType = VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO;
  signals[0].semaphore = timeline.handle();
  signals[0].value = signal_value;
  signals[0].stageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
  signals[1].sType = VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO;
  signals[1].semaphore = signal_binary;
  signals[1].stageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;

  VkSubmitInfo2 submit{};
  submit.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO_2;
  submit.waitSemaphoreInfoCount = wait_binary != VK_NULL_HANDLE ? 1 : 0;
  submit.pWaitSemaphoreInfos = &wait;
  submit.commandBufferInfoCount = 1;
  submit.pCommandBufferInfos = &command_info;
  submit.signalSemaphoreInfoCount = signal_binary != VK_NULL_HANDLE ? 2 : 1;
  submit.pSignalSemaphoreInfos = signals;
  check(vkQueueSubmit2(device.queue(), 1, &submit, VK_NULL_HANDLE),
        "vkQueueSubmit2 (timeline value " + std::to_string(signal_value) + ")");
}

void memoryBarrier(VkCommandBuffer commands, VkPipelineStageFlags2 src_stages, VkAccessFlags2 src_access,
                   VkPipelineStageFlags2 dst_stages, VkAccessFlags2 dst_access) {
  VkMemoryBarrier2 barrier{};
  barrier.sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER_2;
  barrier.srcStageMask = src_stages;
  barrier.srcAccessMask = src_access;
  barrier.dstStageMask = dst_stages;
  barrier.dstAccessMask = dst_access;
  VkDependencyInfo dependency{};
  dependency.sType = VK_STRUCTURE_TYPE_DEPENDENCY_INFO;
  dependency.memoryBarrierCount = 1;
  dependency.pMemoryBarriers = &barrier;
  vkCmdPipelineBarrier2(commands, &dependency);
}

void imageBarrier(VkCommandBuffer commands, VkImage image, VkImageLayout from, VkImageLayout to,
                  VkPipelineStageFlags2 src_stages, VkAccessFlags2 src_access, VkPipelineStageFlags2 dst_stages,
                  VkAccessFlags2 dst_access, VkImageAspectFlags aspect) {
  VkImageMemoryBarrier2 barrier{};
  barrier.sType = VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2;
  barrier.srcStageMask = src_stages;
  barrier.srcAccessMask = src_access;
  barrier.dstStageMask = dst_stages;
  barrier.dstAccessMask = dst_access;
  barrier.oldLayout = from;
  barrier.newLayout = to;
  barrier.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  barrier.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  barrier.image = image;
  barrier.subresourceRange = {aspect, 0, 1, 0, 1};
  VkDependencyInfo dependency{};
  dependency.sType = VK_STRUCTURE_TYPE_DEPENDENCY_INFO;
  dependency.imageMemoryBarrierCount = 1;
  dependency.pImageMemoryBarriers = &barrier;
  vkCmdPipelineBarrier2(commands, &dependency);
}

}  // namespace plumb::gpu
