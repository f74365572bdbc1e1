#pragma once
// What the GPU tests share: the device they run on, a plain buffer to play with, and the rule
// that any validation message fails.

#include <gtest/gtest.h>
#include <vulkan/vulkan.h>

#include <memory>
#include <string>

#include "engine/gpu/device.h"
#include "engine/gpu/instance.h"
#include "engine/gpu/memory.h"
#include "engine/gpu/vk_check.h"

namespace plumb::test {

// PLUMB_GPU's choice, lavapipe when unset: the tests' results must not depend on what card the
// machine happens to have.
inline gpu::DeviceChoice testDeviceChoice() {
  gpu::DeviceChoice choice = gpu::deviceChoiceFromEnvironment();
  if (choice.prefer.empty()) choice.prefer = "cpu";
  return choice;
}

// A buffer without memory; the caller destroys it.
inline VkBuffer createBuffer(const gpu::Device& device, VkDeviceSize size,
                             VkBufferUsageFlags usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT) {
  VkBufferCreateInfo create{};
  create.sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO;
  create.size = size;
  create.usage = usage;
  VkBuffer buffer = VK_NULL_HANDLE;
  gpu::check(vkCreateBuffer(device.handle(), &create, nullptr, &buffer), "vkCreateBuffer");
  return buffer;
}

// Every validation message the instance recorded is a failure of the test.
inline void expectNoValidationMessages(const gpu::Instance& instance) {
  for (const std::string& message : instance.validationMessages()) ADD_FAILURE() << message;
}

// A fixture whose tests each get a device (testDeviceChoice) and its allocator, with validation
// on: any message the layer records fails the test.
class GpuTest : public ::testing::Test {
 protected:
  void SetUp() override {
    instance_ = std::make_unique<gpu::Instance>(gpu::InstanceOptions{.validation = true});
    device_ = std::make_unique<gpu::Device>(*instance_, testDeviceChoice());
    allocator_ = std::make_unique<gpu::MemoryAllocator>(*device_);
  }
  void TearDown() override {
    allocator_.reset();
    device_.reset();
    expectNoValidationMessages(*instance_);
  }

  std::unique_ptr<gpu::Instance> instance_;
  std::unique_ptr<gpu::Device> device_;
  std::unique_ptr<gpu::MemoryAllocator> allocator_;
};

}  // namespace plumb::test
