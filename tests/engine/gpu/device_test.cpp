// The Vulkan instance and device on this machine's lavapipe (or the GPU PLUMB_GPU names), with
// validation on: any validation message fails the test that caused it.

#include "engine/gpu/device.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <functional>
#include <limits>
#include <vector>

#include "engine/gpu/instance.h"
#include "engine/gpu/memory.h"
#include "engine/gpu/vk_check.h"
#include "tests/support/gpu_test.h"

namespace plumb::gpu {
namespace {

constexpr std::uint32_t kVisibilityMin[] =
#include "shaders/visibility_min.comp.inc"
    ;

// Runs `destroy` at scope exit: the test's own objects, released in reverse order.
class Defer {
 public:
  explicit Defer(std::function<void()> destroy) : destroy_(std::move(destroy)) {}
  ~Defer() { destroy_(); }
  Defer(const Defer&) = delete;
  Defer& operator=(const Defer&) = delete;

 private:
  std::function<void()> destroy_;
};

class GpuTest : public ::testing::Test {
 protected:
  void SetUp() override { test::keepVulkanDriverLoaded(); }
};

TEST_F(GpuTest, DeviceWithTheRenderersFeaturesUnderValidation) {
  const Instance instance({.validation = true});
  ASSERT_TRUE(instance.validating());
  {
    const Device device(instance, test::testDeviceChoice());
    std::printf("device: %s (Vulkan %u.%u)\n", device.name().c_str(),
                VK_API_VERSION_MAJOR(device.properties().apiVersion),
                VK_API_VERSION_MINOR(device.properties().apiVersion));
    EXPECT_NE(device.queue(), VK_NULL_HANDLE);
    EXPECT_GE(device.properties().apiVersion, VK_API_VERSION_1_3);
  }
  test::expectNoValidationMessages(instance);
}

TEST_F(GpuTest, ANameNoDeviceHasIsAClearError) {
  const Instance instance;
  try {
    const Device device(instance, {.prefer = "no such device 4711"});
    FAIL() << "a device was chosen";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("is not 'no such device 4711'"), std::string::npos) << error.what();
  }
}

TEST_F(GpuTest, TheValidationLayerIsHeard) {
  const Instance instance({.validation = true});
  {
    const Device device(instance, test::testDeviceChoice());
    // A buffer without usage flags breaks a valid-usage rule the layer checks.
    VkBufferCreateInfo create{};
    create.sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO;
    create.size = 256;
    create.usage = 0;
    VkBuffer buffer = VK_NULL_HANDLE;
    if (vkCreateBuffer(device.handle(), &create, nullptr, &buffer) == VK_SUCCESS)
      vkDestroyBuffer(device.handle(), buffer, nullptr);
  }
  const auto messages = instance.validationMessages();
  ASSERT_FALSE(messages.empty());
  EXPECT_NE(messages.front().find("VUID-VkBufferCreateInfo-usage"), std::string::npos) << messages.front();
}

// 2^20 samples on 4,096 pixels: the nearest sample of each pixel wins, ties to the lower id.
TEST_F(GpuTest, SixtyFourBitAtomicMinKeepsTheNearestSampleOfEachPixel) {
  struct Sample {
    std::uint32_t pixel;
    float depth;
  };
  constexpr std::uint32_t kSamples = 1u << 20, kPixels = 4096;
  std::vector<Sample> samples(kSamples);
  for (std::uint32_t i = 0; i < kSamples; ++i) {
    const std::uint64_t h = (i + 1) * 0x9E3779B97F4A7C15ULL;
    samples[i] = {static_cast<std::uint32_t>(h >> 40) % kPixels, static_cast<float>((h >> 8) % 1000) * 0.25f};
  }
  std::vector<std::uint64_t> expected(kPixels, std::numeric_limits<std::uint64_t>::max());
  for (std::uint32_t i = 0; i < kSamples; ++i) {
    std::uint32_t bits = 0;
    std::memcpy(&bits, &samples[i].depth, sizeof bits);
    expected[samples[i].pixel] = std::min(expected[samples[i].pixel], (std::uint64_t{bits} << 32) | i);
  }

  const Instance instance({.validation = true});
  {
    const Device device(instance, test::testDeviceChoice());
    const VkDevice d = device.handle();
    // Host-visible storage buffers: enough for a check of the atomics; the renderer streams
    // through device-local memory.
    MemoryAllocator allocator(device);
    const VkBuffer sample_buffer = test::createBuffer(device, sizeof(Sample) * kSamples);
    const VkBuffer visibility_buffer = test::createBuffer(device, sizeof(std::uint64_t) * kPixels);
    const Defer free_buffers([&] {
      vkDestroyBuffer(d, sample_buffer, nullptr);
      vkDestroyBuffer(d, visibility_buffer, nullptr);
    });
    auto bindHostMemory = [&](VkBuffer buffer) {
      VkMemoryRequirements requirements;
      vkGetBufferMemoryRequirements(d, buffer, &requirements);
      Allocation allocation =
          allocator.allocate(requirements, VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT);
      check(vkBindBufferMemory(d, buffer, allocation.memory(), allocation.offset()), "vkBindBufferMemory");
      return allocation;
    };
    const Allocation sample_memory = bindHostMemory(sample_buffer);
    const Allocation visibility_memory = bindHostMemory(visibility_buffer);
    std::memcpy(sample_memory.mapped(), samples.data(), sizeof(Sample) * kSamples);
    std::fill_n(static_cast<std::uint64_t*>(visibility_memory.mapped()), kPixels,
                std::numeric_limits<std::uint64_t>::max());

    std::array<VkDescriptorSetLayoutBinding, 2> bindings{};
    for (std::uint32_t b = 0; b < 2; ++b) {
      bindings[b].binding = b;
      bindings[b].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
      bindings[b].descriptorCount = 1;
      bindings[b].stageFlags = VK_SHADER_STAGE_COMPUTE_BIT;
    }
    VkDescriptorSetLayoutCreateInfo layout_info{};
    layout_info.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO;
    layout_info.bindingCount = 2;
    layout_info.pBindings = bindings.data();
    VkDescriptorSetLayout set_layout = VK_NULL_HANDLE;
    check(vkCreateDescriptorSetLayout(d, &layout_info, nullptr, &set_layout), "vkCreateDescriptorSetLayout");
    const Defer free_set_layout([&] { vkDestroyDescriptorSetLayout(d, set_layout, nullptr); });
    VkPushConstantRange push{VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(std::uint32_t)};
    VkPipelineLayoutCreateInfo pipeline_layout_info{};
    pipeline_layout_info.sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO;
    pipeline_layout_info.setLayoutCount = 1;
    pipeline_layout_info.pSetLayouts = &set_layout;
    pipeline_layout_info.pushConstantRangeCount = 1;
    pipeline_layout_info.pPushConstantRanges = &push;
    VkPipelineLayout pipeline_layout = VK_NULL_HANDLE;
    check(vkCreatePipelineLayout(d, &pipeline_layout_info, nullptr, &pipeline_layout), "vkCreatePipelineLayout");
    const Defer free_pipeline_layout([&] { vkDestroyPipelineLayout(d, pipeline_layout, nullptr); });

    VkShaderModuleCreateInfo module_info{};
    module_info.sType = VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO;
    module_info.codeSize = sizeof kVisibilityMin;
    module_info.pCode = kVisibilityMin;
    VkShaderModule module = VK_NULL_HANDLE;
    check(vkCreateShaderModule(d, &module_info, nullptr, &module), "vkCreateShaderModule");
    const Defer free_module([&] { vkDestroyShaderModule(d, module, nullptr); });
    VkComputePipelineCreateInfo pipeline_info{};
    pipeline_info.sType = VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO;
    pipeline_info.stage.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO;
    pipeline_info.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
    pipeline_info.stage.module = module;
    pipeline_info.stage.pName = "main";
    pipeline_info.layout = pipeline_layout;
    VkPipeline pipeline = VK_NULL_HANDLE;
    check(vkCreateComputePipelines(d, VK_NULL_HANDLE, 1, &pipeline_info, nullptr, &pipeline),
          "vkCreateComputePipelines");
    const Defer free_pipeline([&] { vkDestroyPipeline(d, pipeline, nullptr); });

    VkDescriptorPoolSize pool_size{VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 2};
    VkDescriptorPoolCreateInfo pool_info{};
    pool_info.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO;
    pool_info.maxSets = 1;
    pool_info.poolSizeCount = 1;
    pool_info.pPoolSizes = &pool_size;
    VkDescriptorPool pool = VK_NULL_HANDLE;
    check(vkCreateDescriptorPool(d, &pool_info, nullptr, &pool), "vkCreateDescriptorPool");
    const Defer free_pool([&] { vkDestroyDescriptorPool(d, pool, nullptr); });
    VkDescriptorSetAllocateInfo set_info{};
    set_info.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO;
    set_info.descriptorPool = pool;
    set_info.descriptorSetCount = 1;
    set_info.pSetLayouts = &set_layout;
    VkDescriptorSet set = VK_NULL_HANDLE;
    check(vkAllocateDescriptorSets(d, &set_info, &set), "vkAllocateDescriptorSets");
    std::array<VkDescriptorBufferInfo, 2> buffer_infos{
        {{sample_buffer, 0, VK_WHOLE_SIZE}, {visibility_buffer, 0, VK_WHOLE_SIZE}}};
    std::array<VkWriteDescriptorSet, 2> writes{};
    for (std::uint32_t b = 0; b < 2; ++b) {
      writes[b].sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET;
      writes[b].dstSet = set;
      writes[b].dstBinding = b;
      writes[b].descriptorCount = 1;
      writes[b].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
      writes[b].pBufferInfo = &buffer_infos[b];
    }
    vkUpdateDescriptorSets(d, 2, writes.data(), 0, nullptr);

    VkCommandPoolCreateInfo command_pool_info{};
    command_pool_info.sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO;
    command_pool_info.queueFamilyIndex = device.queueFamily();
    VkCommandPool command_pool = VK_NULL_HANDLE;
    check(vkCreateCommandPool(d, &command_pool_info, nullptr, &command_pool), "vkCreateCommandPool");
    const Defer free_command_pool([&] { vkDestroyCommandPool(d, command_pool, nullptr); });
    VkCommandBufferAllocateInfo command_info{};
    command_info.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO;
    command_info.commandPool = command_pool;
    command_info.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    command_info.commandBufferCount = 1;
    VkCommandBuffer commands = VK_NULL_HANDLE;
    check(vkAllocateCommandBuffers(d, &command_info, &commands), "vkAllocateCommandBuffers");
    VkCommandBufferBeginInfo begin{};
    begin.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO;
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    check(vkBeginCommandBuffer(commands, &begin), "vkBeginCommandBuffer");
    vkCmdBindPipeline(commands, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline);
    vkCmdBindDescriptorSets(commands, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline_layout, 0, 1, &set, 0, nullptr);
    vkCmdPushConstants(commands, pipeline_layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof kSamples, &kSamples);
    vkCmdDispatch(commands, kSamples / 64, 1, 1);
    // The host reads the result after the fence: make the shader's writes visible to it.
    VkMemoryBarrier to_host{};
    to_host.sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER;
    to_host.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT;
    to_host.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
    vkCmdPipelineBarrier(commands, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &to_host, 0,
                         nullptr, 0, nullptr);
    check(vkEndCommandBuffer(commands), "vkEndCommandBuffer");

    VkFenceCreateInfo fence_info{};
    fence_info.sType = VK_STRUCTURE_TYPE_FENCE_CREATE_INFO;
    VkFence fence = VK_NULL_HANDLE;
    check(vkCreateFence(d, &fence_info, nullptr, &fence), "vkCreateFence");
    const Defer free_fence([&] { vkDestroyFence(d, fence, nullptr); });
    VkSubmitInfo submit{};
    submit.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO;
    submit.commandBufferCount = 1;
    submit.pCommandBuffers = &commands;
    check(vkQueueSubmit(device.queue(), 1, &submit, fence), "vkQueueSubmit");
    check(vkWaitForFences(d, 1, &fence, VK_TRUE, 60'000'000'000ull), "vkWaitForFences");

    const auto* visibility = static_cast<const std::uint64_t*>(visibility_memory.mapped());
    std::uint32_t wrong = 0;
    for (std::uint32_t p = 0; p < kPixels; ++p) wrong += visibility[p] == expected[p] ? 0u : 1u;
    EXPECT_EQ(wrong, 0u) << "of " << kPixels << " pixels";
  }
  test::expectNoValidationMessages(instance);
}

}  // namespace
}  // namespace plumb::gpu
