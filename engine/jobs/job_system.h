#pragma once
// The job system: small closures on oneTBB worker threads, in three priorities, each with a
// cancellation token, and a queue of continuations that the main thread drains once per frame.
//
//   JobSystem jobs;
//   JobHandle grow = jobs.submit(Priority::interactive, "grow", [&](const CancelToken& cancel) {
//     GrowSnapshot result = growRegions(cache, parameters, options_with(cancel.flag()));
//     jobs.post([result] { applyToScene(result); });  // runs on the main thread, next frame
//   });
//   ...
//   grow.cancel();                 // a newer click
//   jobs.drainContinuations();     // main thread, once per frame
//
// Interactive work (a grow the user waits for) runs ahead of streaming (octree nodes the view
// needs), which runs ahead of background work (an import): each priority is a oneTBB task arena,
// and free workers go to the highest arena with work. A running job is never preempted; long
// jobs check their token between steps. Nothing here sleeps to wait.

#include <array>
#include <atomic>
#include <condition_variable>
#include <cstddef>
#include <deque>
#include <exception>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

namespace plumb::jobs {

enum class Priority { interactive, streaming, background };
inline constexpr std::size_t kPriorityCount = 3;

const char* priorityName(Priority priority);

// Shared state of one job: its cancel flag, whether it has finished, and its failure if any.
struct JobState {
  std::string name;
  std::atomic<bool> cancelled{false};
  std::atomic<bool> finished{false};
  std::exception_ptr error;  // written by the job before `finished` is set, read after
};

// What a job sees of its cancellation. Cheap to copy; valid as long as any copy or handle lives.
class CancelToken {
 public:
  explicit CancelToken(std::shared_ptr<JobState> state) : state_(std::move(state)) {}
  bool cancelled() const { return state_->cancelled.load(std::memory_order_relaxed); }
  // For APIs that take a flag (reco::GrowOptions::cancel): true once the job is cancelled.
  // cancel() notifies it, so a job may also block on it: flag()->wait(false).
  const std::atomic<bool>* flag() const { return &state_->cancelled; }

 private:
  std::shared_ptr<JobState> state_;
};

// The submitter's side of a job. A default-constructed handle refers to no job.
class JobHandle {
 public:
  JobHandle() = default;
  explicit JobHandle(std::shared_ptr<JobState> state) : state_(std::move(state)) {}

  bool valid() const { return state_ != nullptr; }
  // Asks the job to stop; it sees the flag at its next check. A job that has not started yet
  // is skipped. Safe from any thread; does nothing on an invalid handle.
  void cancel() const;
  bool cancelled() const;
  bool finished() const;
  // Blocks until the job has finished or been skipped (tests and shutdown; never in a frame).
  void wait() const;
  // The exception the job threw, if it threw; valid once finished().
  std::exception_ptr error() const;
  const std::string& name() const;

 private:
  std::shared_ptr<JobState> state_;
};

struct JobSystemOptions {
  // Worker threads for all priorities together; 0: the hardware's threads, but at least 2, so a
  // long interactive job never leaves streaming without a thread on a two-core machine.
  unsigned worker_threads = 0;
};

class JobSystem {
 public:
  using Work = std::function<void(const CancelToken&)>;

  explicit JobSystem(const JobSystemOptions& options = {});
  // Cancels the running jobs and waits for them to return; skips the queued ones (their handles
  // finish, cancelled); drops the continuations never drained.
  ~JobSystem();
  JobSystem(const JobSystem&) = delete;
  JobSystem& operator=(const JobSystem&) = delete;

  // Runs `work` on a worker thread at `priority`. Thread-safe. An exception thrown by `work`
  // is caught and kept in the handle (JobHandle::error); it never reaches another job.
  JobHandle submit(Priority priority, std::string name, Work work);

  // Queues `continuation` for the main thread's next drainContinuations(). Thread-safe; the
  // usual way for a job to hand its result back (applied at a frame boundary).
  void post(std::function<void()> continuation);

  // Main thread, once per frame: runs the continuations posted so far, in the order posted.
  // Those that post again run at the next drain. Returns how many ran.
  std::size_t drainContinuations();

  // Called (from the posting thread) whenever a continuation is posted, so an event loop that
  // waits for input can wake up: glfwPostEmptyEvent. Set it before submitting work.
  void setWakeUp(std::function<void()> wake_up);

  // Blocks until no job of any priority is queued or running, those that jobs submit meanwhile
  // included (tests, shutdown, headless runs). What the jobs wrote is then visible.
  void waitIdle();

  // Jobs submitted and not yet finished, for the status bar.
  std::size_t pending() const;
  unsigned workerThreads() const { return worker_threads_; }

 private:
  struct Arenas;  // the oneTBB objects, kept out of this header
  struct RunNextTask;
  struct Queued {
    std::shared_ptr<JobState> state;
    Work work;
  };

  // Runs (or skips) the oldest queued job of a priority; one oneTBB task per submitted job.
  void runNext(std::size_t priority);
  void finish(JobState& state);

  unsigned worker_threads_;
  std::unique_ptr<Arenas> arenas_;

  // Jobs travel to the workers through these queues rather than inside oneTBB's tasks: the
  // mutex is a hand-over that ThreadSanitizer sees (Debian's libtbb is not instrumented).
  mutable std::mutex jobs_mutex_;
  std::condition_variable idle_;  // pending_ fell to zero
  std::size_t pending_ = 0;       // submitted and not finished
  std::array<std::deque<Queued>, kPriorityCount> queued_;
  std::vector<std::shared_ptr<JobState>> running_;  // for the destructor to cancel
  bool stopping_ = false;                           // set by the destructor: queued jobs are skipped

  std::mutex continuations_mutex_;
  std::vector<std::function<void()>> continuations_;
  std::function<void()> wake_up_;
};

}  // namespace plumb::jobs
