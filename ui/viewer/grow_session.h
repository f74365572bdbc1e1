#pragma once
// The viewer's one grow at a time: a click starts a grower job at interactive priority and
// cancels the one before it; its progress snapshots reach the main thread as continuations of
// the job system, coalesced (a frame sees only the newest), and those of a cancelled grow are
// dropped there, so a stale snapshot never overwrites a newer click's.

#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>

#include "engine/jobs/job_system.h"
#include "reco/parameters.h"
#include "reco/region_grower.h"

namespace plumb::lod {
class NodeCache;
}

namespace plumb::viewer {

struct GrowUpdate {
  std::uint64_t grow = 0;  // which start() this belongs to, counting from 1
  reco::GrowParameters parameters;
  reco::GrowSnapshot snapshot;
  bool final = false;               // the grow has ended (converged or cancelled)
  double first_progress_ms = -1.0;  // when the grow published its first snapshot
};

class GrowSession {
 public:
  // `on_update` runs on the main thread, inside JobSystem::drainContinuations.
  GrowSession(jobs::JobSystem& jobs, lod::NodeCache& cache, std::function<void(const GrowUpdate&)> on_update);
  // Cancels the running grow and waits for it.
  ~GrowSession();
  GrowSession(const GrowSession&) = delete;
  GrowSession& operator=(const GrowSession&) = delete;

  // Cancels the running grow (if any) and starts one; returns its number.
  std::uint64_t start(const reco::GrowParameters& parameters, reco::GrowOptions options = {});
  void cancel();
  // A grow has been started and its final update not applied yet.
  bool busy() const { return busy_; }
  std::uint64_t current() const { return current_; }

 private:
  // Shared with the job: the newest snapshot not yet handed to the main thread.
  struct Mailbox {
    std::mutex mutex;
    std::optional<GrowUpdate> pending;
  };
  void deliver(const std::shared_ptr<Mailbox>& mailbox);

  jobs::JobSystem& jobs_;
  lod::NodeCache& cache_;
  std::function<void(const GrowUpdate&)> on_update_;
  jobs::JobHandle job_;
  std::shared_ptr<std::atomic<bool>> cancel_;  // the running grow's
  // False once this session is gone: a job's last continuation may still be queued then (the
  // viewer replaces the session when an import's whole cloud follows its preview). Main thread.
  std::shared_ptr<bool> alive_ = std::make_shared<bool>(true);
  std::uint64_t current_ = 0;
  bool busy_ = false;
};

}  // namespace plumb::viewer
