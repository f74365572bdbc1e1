// The Vulkan instance and device on this machine's lavapipe (or the GPU PLUMB_GPU names), with
// validation on: any validation message fails the test that caused it.

#include "engine/gpu/device.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <limits>
#include <vector>

#include "engine/gpu/buffer.h"
#include "engine/gpu/commands.h"
#include "engine/gpu/compute_pipeline.h"
#include "engine/gpu/instance.h"
#include "engine/gpu/memory.h"
#include "engine/gpu/timeline.h"
#include "engine/gpu/vk_check.h"
#include "tests/support/gpu_test.h"

namespace plumb::gpu {
namespace {

constexpr std::uint32_t kVisibilityMin[] =
#include "shaders/visibility_min.comp.inc"
    ;

using GpuTest = ::testing::Test;

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
    // Host-visible storage buffers: enough for a check of the atomics; the renderer streams
    // through device-local memory.
    MemoryAllocator allocator(device);
    Buffer sample_buffer(device, allocator, sizeof(Sample) * kSamples, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, kHostMemory,
                         "samples");
    Buffer visibility(device, allocator, sizeof(std::uint64_t) * kPixels, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                      kHostMemory, "visibility");
    std::memcpy(sample_buffer.mapped(), samples.data(), sizeof(Sample) * kSamples);
    std::fill_n(static_cast<std::uint64_t*>(visibility.mapped()), kPixels, std::numeric_limits<std::uint64_t>::max());

    struct Push {
      VkDeviceAddress samples, visibility;
      std::uint32_t sample_count, reserved;
    };
    const ComputePipeline pipeline(device, kVisibilityMin, sizeof(Push), "visibility min");
    CommandPool pool(device, "test");
    TimelineSemaphore timeline(device);
    VkCommandBuffer commands = pool.begin();
    pipeline.dispatch(commands, Push{sample_buffer.address(), visibility.address(), kSamples, 0}, kSamples / 64);
    // The host reads the result after the wait: make the shader's writes visible to it.
    memoryBarrier(commands, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_WRITE_BIT,
                  VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT);
    submit(device, commands, timeline, 1);
    ASSERT_TRUE(timeline.wait(1, std::uint64_t{10'000'000'000}));

    const auto* result = static_cast<const std::uint64_t*>(visibility.mapped());
    std::size_t wrong = 0;
    for (std::uint32_t p = 0; p < kPixels; ++p) wrong += result[p] != expected[p];
    EXPECT_EQ(wrong, 0u) << "of " << kPixels << " pixels";
  }
  test::expectNoValidationMessages(instance);
}

}  // namespace
}  // namespace plumb::gpu
