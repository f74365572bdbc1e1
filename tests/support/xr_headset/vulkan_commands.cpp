// One-off submissions on the application's queue (vulkan_commands.h), as XR_KHR_vulkan_enable2
// allows (OpenXR 1.0 specification, chapter 12, section "XR_KHR_vulkan_enable2").

#include "tests/support/xr_headset/vulkan_commands.h"

#include <cstdio>

namespace plumb::xr_headset {
namespace {

// Long enough for lavapipe on a loaded machine; a wait past it means the device hangs.
constexpr std::uint64_t kFenceTimeoutNs = 60'000'000'000;

}  // namespace

bool vulkanSucceeded(VkResult result, const char* call) {
  if (result == VK_SUCCESS) return true;
  std::fprintf(stderr, "simulated headset: %s failed with VkResult %d\n", call, static_cast<int>(result));
  return false;
}

std::optional<std::uint32_t> findMemoryType(VkPhysicalDevice physical_device, std::uint32_t type_bits,
                                            VkMemoryPropertyFlags required, VkMemoryPropertyFlags preferred) {
  VkPhysicalDeviceMemoryProperties properties{};
  vkGetPhysicalDeviceMemoryProperties(physical_device, &properties);
  std::optional<std::uint32_t> fallback;
  for (std::uint32_t i = 0; i < properties.memoryTypeCount; ++i) {
    if ((type_bits & (1u << i)) == 0) continue;
    const VkMemoryPropertyFlags flags = properties.memoryTypes[i].propertyFlags;
    if ((flags & required) != required) continue;
    if ((flags & preferred) == preferred) return i;
    if (!fallback) fallback = i;
  }
  return fallback;
}

std::unique_ptr<OneShotCommands> OneShotCommands::create(const VulkanBinding& binding) {
  std::unique_ptr<OneShotCommands> commands(new OneShotCommands(binding));
  VkCommandPoolCreateInfo pool_info{};
  pool_info.sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO;
  pool_info.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT | VK_COMMAND_POOL_CREATE_TRANSIENT_BIT;
  pool_info.queueFamilyIndex = binding.queue_family_index;
  if (!vulkanSucceeded(vkCreateCommandPool(binding.device, &pool_info, nullptr, &commands->pool_),
                       "vkCreateCommandPool")) {
    return nullptr;
  }
  VkCommandBufferAllocateInfo buffer_info{};
  buffer_info.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO;
  buffer_info.commandPool = commands->pool_;
  buffer_info.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  buffer_info.commandBufferCount = 1;
  if (!vulkanSucceeded(vkAllocateCommandBuffers(binding.device, &buffer_info, &commands->buffer_),
                       "vkAllocateCommandBuffers")) {
    return nullptr;
  }
  VkFenceCreateInfo fence_info{};
  fence_info.sType = VK_STRUCTURE_TYPE_FENCE_CREATE_INFO;
  if (!vulkanSucceeded(vkCreateFence(binding.device, &fence_info, nullptr, &commands->fence_), "vkCreateFence")) {
    return nullptr;
  }
  return commands;
}

OneShotCommands::~OneShotCommands() {
  // Every submission was waited for in run(): nothing of ours is in flight.
  if (fence_ != VK_NULL_HANDLE) vkDestroyFence(binding_.device, fence_, nullptr);
  if (pool_ != VK_NULL_HANDLE) vkDestroyCommandPool(binding_.device, pool_, nullptr);
}

bool OneShotCommands::run(const std::function<void(VkCommandBuffer)>& record) {
  VkCommandBufferBeginInfo begin{};
  begin.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO;
  begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  if (!vulkanSucceeded(vkBeginCommandBuffer(buffer_, &begin), "vkBeginCommandBuffer")) return false;
  record(buffer_);
  if (!vulkanSucceeded(vkEndCommandBuffer(buffer_), "vkEndCommandBuffer")) return false;
  if (!vulkanSucceeded(vkResetFences(binding_.device, 1, &fence_), "vkResetFences")) return false;
  VkSubmitInfo submit{};
  submit.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO;
  submit.commandBufferCount = 1;
  submit.pCommandBuffers = &buffer_;
  if (!vulkanSucceeded(vkQueueSubmit(binding_.queue, 1, &submit, fence_), "vkQueueSubmit")) return false;
  return vulkanSucceeded(vkWaitForFences(binding_.device, 1, &fence_, VK_TRUE, kFenceTimeoutNs), "vkWaitForFences");
}

}  // namespace plumb::xr_headset
