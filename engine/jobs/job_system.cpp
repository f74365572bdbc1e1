#include "engine/jobs/job_system.h"

#include <oneapi/tbb/global_control.h>
#include <oneapi/tbb/task_arena.h>

#include <algorithm>
#include <array>
#include <cassert>
#include <thread>

#include "engine/core/tsan_handover.h"

// submit() releases, the task acquires when it starts (engine/core/tsan_handover.h).

namespace plumb::jobs {

const char* priorityName(Priority priority) {
  switch (priority) {
    case Priority::interactive:
      return "interactive";
    case Priority::streaming:
      return "streaming";
    case Priority::background:
      return "background";
  }
  return "unknown";
}

namespace {

void cancelJob(JobState& state) {
  state.cancelled.store(true, std::memory_order_relaxed);
  state.cancelled.notify_all();
}

}  // namespace

void JobHandle::cancel() const {
  if (state_) cancelJob(*state_);
}

bool JobHandle::cancelled() const {
  return state_ && state_->cancelled.load(std::memory_order_relaxed);
}

bool JobHandle::finished() const {
  return state_ && state_->finished.load(std::memory_order_acquire);
}

void JobHandle::wait() const {
  if (!state_) return;
  state_->finished.wait(false, std::memory_order_acquire);
}

std::exception_ptr JobHandle::error() const {
  return finished() ? state_->error : nullptr;
}

const std::string& JobHandle::name() const {
  static const std::string kNone;
  return state_ ? state_->name : kNone;
}

// One arena per priority. An arena's concurrency is all workers, so a lone priority with work
// uses the whole machine; with several, oneTBB gives free workers to the highest first.
struct JobSystem::Arenas {
  explicit Arenas(unsigned threads)
      // The main thread never joins the arenas (it only submits), so every thread is a worker.
      : parallelism(tbb::global_control::max_allowed_parallelism, threads + 1),
        arenas{tbb::task_arena(static_cast<int>(threads), 0, tbb::task_arena::priority::high),
               tbb::task_arena(static_cast<int>(threads), 0, tbb::task_arena::priority::normal),
               tbb::task_arena(static_cast<int>(threads), 0, tbb::task_arena::priority::low)} {}

  tbb::global_control parallelism;
  std::array<tbb::task_arena, kPriorityCount> arenas;
};

// The oneTBB task of one submitted job. A named type, so that ThreadSanitizer's suppression of
// the reads of its two members can name it (tests/engine/jobs/tsan.supp).
struct JobSystem::RunNextTask {
  JobSystem* system;
  std::size_t priority;
  void operator()() const {
    PLUMB_TSAN_ACQUIRE(system);
    system->runNext(priority);
  }
};

JobSystem::JobSystem(const JobSystemOptions& options)
    : worker_threads_(options.worker_threads > 0 ? options.worker_threads
                                                 : std::max(2u, std::thread::hardware_concurrency())),
      arenas_(std::make_unique<Arenas>(worker_threads_)) {}

JobSystem::~JobSystem() {
  {
    const std::scoped_lock lock(jobs_mutex_);
    stopping_ = true;
    for (const std::shared_ptr<JobState>& state : running_) cancelJob(*state);
  }
  waitIdle();
}

JobHandle JobSystem::submit(Priority priority, std::string name, Work work) {
  auto state = std::make_shared<JobState>();
  state->name = std::move(name);
  const auto p = static_cast<std::size_t>(priority);
  {
    const std::scoped_lock lock(jobs_mutex_);
    queued_[p].push_back({state, std::move(work)});
    ++pending_;
  }
  PLUMB_TSAN_RELEASE(this);
  // enqueue, not execute: the caller never joins an arena, so it never waits for a slot.
  arenas_->arenas[p].enqueue(RunNextTask{this, p});
  return JobHandle(state);
}

void JobSystem::runNext(std::size_t priority) {
  Queued job;
  bool run = false;
  {
    const std::scoped_lock lock(jobs_mutex_);
    assert(!queued_[priority].empty() && "one oneTBB task per queued job");
    job = std::move(queued_[priority].front());
    queued_[priority].pop_front();
    if (stopping_) cancelJob(*job.state);
    run = !job.state->cancelled.load(std::memory_order_relaxed);
    if (run) running_.push_back(job.state);
  }
  if (run) {
    try {
      job.work(CancelToken(job.state));
    } catch (...) {
      job.state->error = std::current_exception();
    }
  }
  finish(*job.state);
}

void JobSystem::finish(JobState& state) {
  state.finished.store(true, std::memory_order_release);
  state.finished.notify_all();
  // Last: once the count is zero under the lock, waitIdle may return and destroy the system.
  const std::scoped_lock lock(jobs_mutex_);
  const auto it = std::find_if(running_.begin(), running_.end(),
                               [&](const std::shared_ptr<JobState>& running) { return running.get() == &state; });
  if (it != running_.end()) {
    *it = std::move(running_.back());
    running_.pop_back();
  }
  if (--pending_ == 0) idle_.notify_all();
}

void JobSystem::post(std::function<void()> continuation) {
  std::function<void()> wake_up;
  {
    const std::scoped_lock lock(continuations_mutex_);
    continuations_.push_back(std::move(continuation));
    wake_up = wake_up_;
  }
  if (wake_up) wake_up();
}

std::size_t JobSystem::drainContinuations() {
  std::vector<std::function<void()>> ready;
  {
    const std::scoped_lock lock(continuations_mutex_);
    ready.swap(continuations_);
  }
  for (const std::function<void()>& continuation : ready) continuation();
  return ready.size();
}

void JobSystem::setWakeUp(std::function<void()> wake_up) {
  const std::scoped_lock lock(continuations_mutex_);
  wake_up_ = std::move(wake_up);
}

void JobSystem::waitIdle() {
  std::unique_lock lock(jobs_mutex_);
  idle_.wait(lock, [&] { return pending_ == 0; });
}

std::size_t JobSystem::pending() const {
  const std::scoped_lock lock(jobs_mutex_);
  return pending_;
}

}  // namespace plumb::jobs
