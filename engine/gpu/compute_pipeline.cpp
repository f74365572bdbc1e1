#include "engine/gpu/compute_pipeline.h"

#include <cassert>

#include "engine/core/error.h"
#include "engine/gpu/device.h"
#include "engine/gpu/vk_check.h"

namespace plumb::gpu {

ComputePipeline::ComputePipeline(const Device& device, std::span<const std::uint32_t> spirv, std::uint32_t push_bytes,
                                 const char* name)
    : device_(device.handle()), name_(name), push_bytes_(push_bytes) {
  if (push_bytes > device.properties().limits.maxPushConstantsSize) {
    throw Error("the Vulkan device " + device.name() + " allows " +
                std::to_string(device.properties().limits.maxPushConstantsSize) + " bytes of push constants, " + name_ +
                " needs " + std::to_string(push_bytes));
  }
  const VkPushConstantRange push{VK_SHADER_STAGE_COMPUTE_BIT, 0, push_bytes};
  VkPipelineLayoutCreateInfo layout{};
  layout.sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO;
  layout.pushConstantRangeCount = push_bytes > 0 ? 1 : 0;
  layout.pPushConstantRanges = &push;
  check(vkCreatePipelineLayout(device_, &layout, nullptr, &layout_), "vkCreatePipelineLayout (" + name_ + ")");
  device.setName(VK_OBJECT_TYPE_PIPELINE_LAYOUT, layout_, name);

  VkShaderModuleCreateInfo module_info{};
  module_info.sType = VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO;
  module_info.codeSize = spirv.size_bytes();
  module_info.pCode = spirv.data();
  VkShaderModule module = VK_NULL_HANDLE;
  try {
    check(vkCreateShaderModule(device_, &module_info, nullptr, &module), "vkCreateShaderModule (" + name_ + ")");
    VkComputePipelineCreateInfo create{};
    create.sType = VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO;
    create.stage.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO;
    create.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
    create.stage.module = module;
    create.stage.pName = "main";
    create.layout = layout_;
    check(vkCreateComputePipelines(device_, VK_NULL_HANDLE, 1, &create, nullptr, &pipeline_),
          "vkCreateComputePipelines (" + name_ + ")");
  } catch (...) {
    vkDestroyShaderModule(device_, module, nullptr);
    vkDestroyPipelineLayout(device_, layout_, nullptr);
    throw;
  }
  vkDestroyShaderModule(device_, module, nullptr);  // the pipeline keeps what it needs
  device.setName(VK_OBJECT_TYPE_PIPELINE, pipeline_, name);
}

ComputePipeline::~ComputePipeline() {
  vkDestroyPipeline(device_, pipeline_, nullptr);
  vkDestroyPipelineLayout(device_, layout_, nullptr);
}

void ComputePipeline::bindAndPush(VkCommandBuffer commands, const void* push, std::uint32_t bytes) const {
  assert(bytes == push_bytes_ && "push constants of another size than the pipeline was made for");
  vkCmdBindPipeline(commands, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline_);
  if (bytes > 0) vkCmdPushConstants(commands, layout_, VK_SHADER_STAGE_COMPUTE_BIT, 0, bytes, push);
}

}  // namespace plumb::gpu
