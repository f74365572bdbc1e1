// The job system: priorities, cancellation, continuations drained on the main thread, failures
// kept in the handle. Also run under ThreadSanitizer (build/tsan, see scripts/test).
//
// Nothing here sleeps: a job that must hold a worker waits on a latch or a future the test
// opens. A test that would deadlock if the system were wrong gives up after a generous
// kDeadlockLimit, which is a hang detector, not a timing assertion.

#include "engine/jobs/job_system.h"

#include <gtest/gtest.h>

#include <chrono>
#include <future>
#include <latch>
#include <mutex>
#include <stdexcept>
#include <thread>
#include <vector>

namespace plumb::jobs {
namespace {

constexpr auto kDeadlockLimit = std::chrono::seconds(60);

// A gate that jobs wait at until the test opens it.
class Gate {
 public:
  void open() { promise_.set_value(); }
  void pass() const { future_.wait(); }

 private:
  std::promise<void> promise_;
  std::shared_future<void> future_ = promise_.get_future().share();
};

TEST(JobSystem, RunsAJobAndReportsItFinished) {
  JobSystem jobs;
  std::atomic<int> ran{0};
  const JobHandle handle = jobs.submit(Priority::interactive, "count", [&](const CancelToken&) { ran = 1; });
  handle.wait();
  EXPECT_TRUE(handle.finished());
  EXPECT_EQ(ran.load(), 1);
  EXPECT_EQ(handle.error(), nullptr);
  EXPECT_EQ(handle.name(), "count");
  jobs.waitIdle();
  EXPECT_EQ(jobs.pending(), 0u);
}

TEST(JobSystem, DefaultHasAtLeastTwoWorkersThatRunAtOnce) {
  JobSystem jobs;
  ASSERT_GE(jobs.workerThreads(), 2u);
  // Each job waits for the other: this finishes only if two run at the same time, which a long
  // grow beside node streaming needs even on a two-core machine.
  std::latch both(2);
  std::promise<void> done;
  std::atomic<int> through{0};
  for (int i = 0; i < 2; ++i) {
    jobs.submit(Priority::interactive, "meet", [&](const CancelToken&) {
      both.arrive_and_wait();
      if (++through == 2) done.set_value();
    });
  }
  EXPECT_EQ(done.get_future().wait_for(kDeadlockLimit), std::future_status::ready);
}

// The job runs until it sees the cancellation: it must see it, after having run (a job that never
// saw it would stop at the deadline instead, with `saw` false).
TEST(JobSystem, ARunningJobSeesItsCancellation) {
  JobSystem jobs;
  std::promise<void> started;
  std::atomic<long> steps{0};
  std::atomic<bool> saw{false};
  const JobHandle handle = jobs.submit(Priority::interactive, "loop", [&](const CancelToken& cancel) {
    const auto deadline = std::chrono::steady_clock::now() + kDeadlockLimit;
    ++steps;
    started.set_value();
    while (!cancel.cancelled() && std::chrono::steady_clock::now() < deadline) ++steps;
    saw = cancel.cancelled();
  });
  started.get_future().wait();
  EXPECT_FALSE(handle.finished());
  handle.cancel();
  handle.wait();
  EXPECT_TRUE(handle.cancelled());
  EXPECT_TRUE(saw) << "the running job never saw its cancellation";
  EXPECT_GE(steps.load(), 1);
}

// Cancelled while it runs (after it started, before it reads its token): the job reads the flag set.
TEST(JobSystem, TheTokenFlagFollowsTheHandle) {
  JobSystem jobs;
  Gate gate;
  std::promise<void> started;
  std::atomic<bool> seen{false};
  const JobHandle handle = jobs.submit(Priority::streaming, "flag", [&](const CancelToken& cancel) {
    started.set_value();
    gate.pass();
    seen = cancel.flag()->load();
  });
  started.get_future().wait();
  handle.cancel();
  gate.open();
  handle.wait();
  EXPECT_TRUE(handle.cancelled());
  EXPECT_TRUE(seen) << "the job's token did not follow its handle's cancel";
}

TEST(JobSystem, AJobCancelledBeforeItStartsIsSkipped) {
  JobSystem jobs(JobSystemOptions{1});
  Gate gate;
  jobs.submit(Priority::interactive, "hold the worker", [&](const CancelToken&) { gate.pass(); });
  std::atomic<bool> ran{false};
  const JobHandle skipped = jobs.submit(Priority::interactive, "skipped", [&](const CancelToken&) { ran = true; });
  skipped.cancel();
  gate.open();
  skipped.wait();
  EXPECT_TRUE(skipped.finished());
  EXPECT_FALSE(ran.load());
}

TEST(JobSystem, InteractiveWorkRunsBeforeStreamingBeforeBackground) {
  JobSystem jobs(JobSystemOptions{1});
  Gate gate;
  std::promise<void> holding;
  jobs.submit(Priority::streaming, "hold the worker", [&](const CancelToken&) {
    holding.set_value();
    gate.pass();
  });
  holding.get_future().wait();  // the one worker is busy: everything below queues

  std::mutex mutex;
  std::vector<Priority> order;
  const auto record = [&](Priority priority) {
    return [&, priority](const CancelToken&) {
      const std::scoped_lock lock(mutex);
      order.push_back(priority);
    };
  };
  for (int i = 0; i < 3; ++i) {
    jobs.submit(Priority::background, "background", record(Priority::background));
    jobs.submit(Priority::streaming, "streaming", record(Priority::streaming));
    jobs.submit(Priority::interactive, "interactive", record(Priority::interactive));
  }
  gate.open();
  jobs.waitIdle();
  ASSERT_EQ(order.size(), 9u);
  for (std::size_t i = 1; i < order.size(); ++i) {
    EXPECT_LE(static_cast<int>(order[i - 1]), static_cast<int>(order[i]))
        << "job " << i << " ran out of priority order";
  }
}

TEST(JobSystem, AThrowingJobKeepsItsErrorAndOthersRunOn) {
  JobSystem jobs;
  const JobHandle failing =
      jobs.submit(Priority::background, "fail", [](const CancelToken&) { throw std::runtime_error("disk full"); });
  std::atomic<bool> ran{false};
  const JobHandle next = jobs.submit(Priority::background, "next", [&](const CancelToken&) { ran = true; });
  failing.wait();
  next.wait();
  ASSERT_NE(failing.error(), nullptr);
  try {
    std::rethrow_exception(failing.error());
  } catch (const std::runtime_error& error) {
    EXPECT_STREQ(error.what(), "disk full");
  }
  EXPECT_TRUE(ran.load());
}

TEST(JobSystem, ContinuationsRunOnTheDrainingThreadInOrder) {
  JobSystem jobs;
  std::atomic<int> wake_up_calls{0};  // the wake-up runs on the posting thread
  jobs.setWakeUp([&] { ++wake_up_calls; });
  std::vector<int> applied;  // touched only by the main thread
  const std::thread::id main_thread = std::this_thread::get_id();
  const JobHandle handle = jobs.submit(Priority::interactive, "produce", [&](const CancelToken&) {
    for (int i = 0; i < 5; ++i) {
      jobs.post([&, i] {
        EXPECT_EQ(std::this_thread::get_id(), main_thread);
        applied.push_back(i);
      });
    }
  });
  handle.wait();
  EXPECT_TRUE(applied.empty()) << "continuations run only when the main thread drains";
  EXPECT_EQ(jobs.drainContinuations(), 5u);
  EXPECT_EQ(applied, (std::vector<int>{0, 1, 2, 3, 4}));
  EXPECT_EQ(wake_up_calls.load(), 5);
  EXPECT_EQ(jobs.drainContinuations(), 0u);
}

TEST(JobSystem, AContinuationPostedWhileDrainingWaitsForTheNextFrame) {
  JobSystem jobs;
  int frame_of_second = -1;
  int frame = 0;
  jobs.post([&] { jobs.post([&] { frame_of_second = frame; }); });
  EXPECT_EQ(jobs.drainContinuations(), 1u);
  EXPECT_EQ(frame_of_second, -1);
  frame = 1;
  EXPECT_EQ(jobs.drainContinuations(), 1u);
  EXPECT_EQ(frame_of_second, 1);
}

TEST(JobSystem, ShuttingDownCancelsTheRunningJobAndSkipsTheQueued) {
  std::vector<JobHandle> handles;
  std::atomic<int> ran{0};
  JobHandle holder;
  {
    JobSystem jobs(JobSystemOptions{1});
    std::promise<void> holding;
    // Holds the one worker until the destructor cancels it.
    holder = jobs.submit(Priority::interactive, "hold the worker", [&](const CancelToken& cancel) {
      holding.set_value();
      cancel.flag()->wait(false);
    });
    holding.get_future().wait();
    for (int i = 0; i < 20; ++i) {
      handles.push_back(jobs.submit(Priority::background, "queued", [&](const CancelToken&) { ++ran; }));
    }
  }
  EXPECT_TRUE(holder.finished());
  EXPECT_TRUE(holder.cancelled());
  for (const JobHandle& handle : handles) {
    EXPECT_TRUE(handle.finished());
    EXPECT_TRUE(handle.cancelled());
  }
  EXPECT_EQ(ran.load(), 0);
}

TEST(JobSystem, ManyProducersManyJobs) {
  JobSystem jobs;
  constexpr int kThreads = 4;
  constexpr int kJobsPerThread = 500;
  std::atomic<long> sum{0};
  std::vector<std::thread> producers;
  for (int t = 0; t < kThreads; ++t) {
    producers.emplace_back([&, t] {
      for (int i = 0; i < kJobsPerThread; ++i) {
        const auto priority = static_cast<Priority>((t + i) % 3);
        jobs.submit(priority, "add", [&, i](const CancelToken&) {
          sum += i;
          jobs.post([] {});
        });
      }
    });
  }
  for (std::thread& producer : producers) producer.join();
  jobs.waitIdle();
  EXPECT_EQ(sum.load(), static_cast<long>(kThreads) * kJobsPerThread * (kJobsPerThread - 1) / 2);
  EXPECT_EQ(jobs.drainContinuations(), static_cast<std::size_t>(kThreads * kJobsPerThread));
  EXPECT_EQ(jobs.pending(), 0u);
}

TEST(JobSystem, PriorityNames) {
  EXPECT_STREQ(priorityName(Priority::interactive), "interactive");
  EXPECT_STREQ(priorityName(Priority::streaming), "streaming");
  EXPECT_STREQ(priorityName(Priority::background), "background");
}

}  // namespace
}  // namespace plumb::jobs
