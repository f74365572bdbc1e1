// What keeps a frame's objects alive while the GPU uses them: the timeline semaphore and the
// deletion queue, on lavapipe (or the GPU PLUMB_GPU names) with validation on.

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "engine/gpu/commands.h"
#include "engine/gpu/deletion_queue.h"
#include "engine/gpu/device.h"
#include "engine/gpu/instance.h"
#include "engine/gpu/timeline.h"
#include "engine/gpu/vk_check.h"
#include "tests/support/gpu_test.h"

namespace plumb::gpu {
namespace {

TEST(DeletionQueue, RunsWhatTheCompletedValueReachesInTheOrderDeferred) {
  std::vector<std::string> ran;
  {
    DeletionQueue queue;
    queue.defer(3, [&] { ran.push_back("c"); });
    queue.defer(1, [&] { ran.push_back("a"); });
    queue.defer(2, [&] { ran.push_back("b1"); });
    queue.defer(2, [&] { ran.push_back("b2"); });
    EXPECT_EQ(queue.collect(0), 0u);
    EXPECT_EQ(queue.collect(2), 3u);
    EXPECT_EQ(ran, (std::vector<std::string>{"a", "b1", "b2"}));
    EXPECT_EQ(queue.pending(), 1u);
    EXPECT_EQ(queue.collect(2), 0u);  // nothing runs twice
  }
  EXPECT_EQ(ran, (std::vector<std::string>{"a", "b1", "b2", "c"}));  // the rest at destruction
}

TEST(TimelineSemaphore, HostSignalsWaitsAndTimesOut) {
  const Instance instance({.validation = true});
  {
    const Device device(instance, test::testDeviceChoice());
    TimelineSemaphore timeline(device, 2);
    EXPECT_EQ(timeline.value(), 2u);
    timeline.signalFromHost(5);
    EXPECT_EQ(timeline.value(), 5u);
    EXPECT_TRUE(timeline.wait(5, 0));
    EXPECT_FALSE(timeline.wait(6, 1'000'000));  // 1 ms: nothing will signal it
  }
  test::expectNoValidationMessages(instance);
}

// A frame's buffer is deferred to the frame's timeline value: it survives while the GPU has not
// signalled that value, and goes once it has.
TEST(TimelineSemaphore, AFramesBufferGoesOnlyAfterTheGpuSignalsItsFrame) {
  const Instance instance({.validation = true});
  {
    const Device device(instance, test::testDeviceChoice());
    TimelineSemaphore timeline(device);
    DeletionQueue deletions;
    const VkBuffer buffer = test::createBuffer(device, 1024);
    bool destroyed = false;
    constexpr std::uint64_t kFrame = 1;
    deletions.defer(kFrame, [&] {
      vkDestroyBuffer(device.handle(), buffer, nullptr);
      destroyed = true;
    });
    EXPECT_EQ(deletions.collect(timeline.value()), 0u);
    EXPECT_FALSE(destroyed);

    // Frame 1's submission (an empty command buffer) signals the timeline.
    CommandPool pool(device, "frame");
    submit(device, pool.begin(), timeline, kFrame);
    ASSERT_TRUE(timeline.wait(kFrame, 10'000'000'000ull));
    EXPECT_EQ(deletions.collect(timeline.value()), 1u);
    EXPECT_TRUE(destroyed);
  }
  test::expectNoValidationMessages(instance);
}

}  // namespace
}  // namespace plumb::gpu
