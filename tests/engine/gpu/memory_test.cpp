// Block allocation of device memory on lavapipe (or the GPU PLUMB_GPU names).

#include "engine/gpu/memory.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <random>
#include <vector>

#include "engine/gpu/device.h"
#include "engine/gpu/instance.h"
#include "engine/gpu/vk_check.h"
#include "tests/support/gpu_test.h"

namespace plumb::gpu {
namespace {

constexpr VkMemoryPropertyFlags kHost = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;

class MemoryTest : public ::testing::Test {
 protected:
  // The memory types a storage buffer may live in, from a real buffer's requirements.
  static std::uint32_t storageTypeBits(const Device& device) {
    const VkBuffer buffer = test::createBuffer(device, 4096);
    VkMemoryRequirements requirements;
    vkGetBufferMemoryRequirements(device.handle(), buffer, &requirements);
    vkDestroyBuffer(device.handle(), buffer, nullptr);
    return requirements.memoryTypeBits;
  }

  // Live allocations never overlap and keep their alignment.
  static void expectDisjointAndAligned(const std::vector<Allocation>& live,
                                       const std::vector<VkDeviceSize>& alignments) {
    struct Range {
      VkDeviceMemory memory;
      VkDeviceSize start, end;
    };
    std::vector<Range> ranges;
    for (std::size_t i = 0; i < live.size(); ++i) {
      if (!live[i]) continue;
      EXPECT_EQ(live[i].offset() % alignments[i], 0u);
      ranges.push_back({live[i].memory(), live[i].offset(), live[i].offset() + live[i].size()});
    }
    std::sort(ranges.begin(), ranges.end(), [](const Range& a, const Range& b) {
      return a.memory != b.memory ? a.memory < b.memory : a.start < b.start;
    });
    for (std::size_t i = 1; i < ranges.size(); ++i) {
      if (ranges[i].memory == ranges[i - 1].memory) {
        EXPECT_LE(ranges[i - 1].end, ranges[i].start);
      }
    }
  }
};

TEST_F(MemoryTest, RangesAreAlignedDisjointAndAllComeBack) {
  const Instance instance({.validation = true});
  {
    const Device device(instance, test::testDeviceChoice());
    MemoryAllocator allocator(device, VkDeviceSize{1} << 20);
    const std::uint32_t type_bits = storageTypeBits(device);
    std::mt19937 random(7);
    std::vector<Allocation> live;
    std::vector<VkDeviceSize> alignments;
    auto allocateSome = [&](int count) {
      for (int i = 0; i < count; ++i) {
        const VkDeviceSize alignment = VkDeviceSize{16} << (random() % 9);  // 16 B to 4 KiB
        const VkMemoryRequirements requirements{1 + random() % (200 << 10), alignment, type_bits};
        live.push_back(allocator.allocate(requirements, kHost));
        alignments.push_back(alignment);
      }
    };
    allocateSome(300);
    expectDisjointAndAligned(live, alignments);
    for (std::size_t i = 0; i < live.size(); ++i) {
      if (random() % 2) live[i] = Allocation();  // frees
    }
    allocateSome(200);
    expectDisjointAndAligned(live, alignments);
    std::printf("%zu blocks of 1 MiB for %.1f MiB in use\n", allocator.blockCount(),
                static_cast<double>(allocator.bytesInUse()) / (1 << 20));
    EXPECT_LT(allocator.bytesReserved(), 2 * allocator.bytesInUse() + (VkDeviceSize{2} << 20));
    live.clear();
    EXPECT_EQ(allocator.bytesInUse(), 0u);
    EXPECT_EQ(allocator.blockCount(), 1u);  // one empty block is kept for the next request
  }
  test::expectNoValidationMessages(instance);
}

TEST_F(MemoryTest, ARequestLargerThanABlockGetsOneOfItsOwn) {
  const Instance instance;
  const Device device(instance, test::testDeviceChoice());
  MemoryAllocator allocator(device, VkDeviceSize{1} << 20);
  const std::uint32_t type_bits = storageTypeBits(device);
  Allocation small = allocator.allocate({4096, 256, type_bits}, kHost);
  {
    const Allocation large = allocator.allocate({VkDeviceSize{3} << 20, 256, type_bits}, kHost);
    EXPECT_EQ(allocator.blockCount(), 2u);
    EXPECT_NE(large.memory(), small.memory());
    EXPECT_EQ(large.offset(), 0u);
  }
  EXPECT_EQ(allocator.blockCount(), 1u);  // freed with its only allocation
}

// Buffers bound to neighbouring ranges, each filled through its mapping with its own pattern:
// the validation layer checks every bind's alignment and bounds, and an overlap would show as a
// pattern overwritten by a neighbour.
TEST_F(MemoryTest, BuffersBoundToTheirRangesPassValidationAndKeepTheirData) {
  const Instance instance({.validation = true});
  {
    const Device device(instance, test::testDeviceChoice());
    MemoryAllocator allocator(device, VkDeviceSize{1} << 20);
    std::vector<VkBuffer> buffers;
    std::vector<Allocation> allocations;
    for (std::uint32_t i = 0; i < 100; ++i) {
      const VkDeviceSize size = 64 + 977 * i;
      const VkBuffer buffer = test::createBuffer(
          device, size, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT);
      VkMemoryRequirements requirements;
      vkGetBufferMemoryRequirements(device.handle(), buffer, &requirements);
      Allocation allocation = allocator.allocate(requirements, kHost);
      check(vkBindBufferMemory(device.handle(), buffer, allocation.memory(), allocation.offset()),
            "vkBindBufferMemory");
      ASSERT_NE(allocation.mapped(), nullptr);
      std::memset(allocation.mapped(), static_cast<int>(i), size);
      buffers.push_back(buffer);
      allocations.push_back(std::move(allocation));
    }
    for (std::uint32_t i = 0; i < 100; ++i) {
      const auto* bytes = static_cast<const std::uint8_t*>(allocations[i].mapped());
      const std::size_t size = 64 + 977 * i;
      EXPECT_EQ(std::count(bytes, bytes + size, static_cast<std::uint8_t>(i)), static_cast<std::ptrdiff_t>(size));
    }
    for (VkBuffer buffer : buffers) vkDestroyBuffer(device.handle(), buffer, nullptr);
  }
  test::expectNoValidationMessages(instance);
}

}  // namespace
}  // namespace plumb::gpu
