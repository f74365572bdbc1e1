#pragma once
// A compute shader as a pipeline that takes all its inputs as push constants (buffer device
// addresses and scalars): no descriptor sets to allocate, update or keep alive.

#include <vulkan/vulkan.h>

#include <cstdint>
#include <span>
#include <string>

namespace plumb::gpu {

class Device;

class ComputePipeline {
 public:
  // `spirv`: the words glslc wrote (shaders/NAME.comp.inc); `push_bytes`: the size of the
  // shader's push constant block, at most the device's maxPushConstantsSize (128 guaranteed).
  ComputePipeline(const Device& device, std::span<const std::uint32_t> spirv, std::uint32_t push_bytes,
                  const char* name);
  ~ComputePipeline();
  ComputePipeline(const ComputePipeline&) = delete;
  ComputePipeline& operator=(const ComputePipeline&) = delete;

  // Binds the pipeline, pushes `push` (push_bytes of it) and dispatches `groups` work groups.
  template <typename Push>
  void dispatch(VkCommandBuffer commands, const Push& push, std::uint32_t groups_x, std::uint32_t groups_y = 1) const {
    static_assert(sizeof(Push) <= 128, "push constants beyond the guaranteed 128 bytes");
    bindAndPush(commands, &push, sizeof(Push));
    vkCmdDispatch(commands, groups_x, groups_y, 1);
  }
  // The same with the group counts read by the GPU from `groups` (a VkDispatchIndirectCommand at
  // `offset`, in a buffer made with INDIRECT_BUFFER usage), as an earlier dispatch wrote them.
  template <typename Push>
  void dispatchIndirect(VkCommandBuffer commands, const Push& push, VkBuffer groups, VkDeviceSize offset) const {
    static_assert(sizeof(Push) <= 128, "push constants beyond the guaranteed 128 bytes");
    bindAndPush(commands, &push, sizeof(Push));
    vkCmdDispatchIndirect(commands, groups, offset);
  }

 private:
  void bindAndPush(VkCommandBuffer commands, const void* push, std::uint32_t bytes) const;

  VkDevice device_;
  std::string name_;
  std::uint32_t push_bytes_;
  VkPipelineLayout layout_ = VK_NULL_HANDLE;
  VkPipeline pipeline_ = VK_NULL_HANDLE;
};

}  // namespace plumb::gpu
