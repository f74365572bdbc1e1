#include "ui/viewer/grow_session.h"

#include <utility>

namespace plumb::viewer {

GrowSession::GrowSession(jobs::JobSystem& jobs, lod::NodeCache& cache, std::function<void(const GrowUpdate&)> on_update)
    : jobs_(jobs), cache_(cache), on_update_(std::move(on_update)) {}

GrowSession::~GrowSession() {
  cancel();
  job_.wait();
  *alive_ = false;  // continuations the job posted find the session gone
}

void GrowSession::cancel() {
  if (cancel_) cancel_->store(true);
}

std::uint64_t GrowSession::start(const reco::GrowParameters& parameters, reco::GrowOptions options) {
  // Cancel first: the old grow stops at its next cell and its last snapshot is dropped on
  // arrival (its number is no longer current). The grow's own flag, not the job's token: a job
  // cancelled before it starts is skipped, and this one must always end with a final update.
  cancel();
  cancel_ = std::make_shared<std::atomic<bool>>(false);
  const std::uint64_t grow = ++current_;
  busy_ = true;
  auto mailbox = std::make_shared<Mailbox>();
  job_ = jobs_.submit(jobs::Priority::interactive, "grow",
                      [this, mailbox, grow, parameters, options, flag = cancel_](const jobs::CancelToken&) mutable {
                        options.cancel = flag.get();
                        double first_ms = -1.0;
                        // Keep only the newest snapshot; wake the main thread only when the box
                        // was empty (it will take whatever is newest then).
                        auto publish = [&](const reco::GrowSnapshot& snapshot, bool final) {
                          bool post = false;
                          {
                            const std::scoped_lock lock(mailbox->mutex);
                            post = !mailbox->pending.has_value();
                            mailbox->pending = GrowUpdate{grow, parameters, snapshot, final, first_ms};
                          }
                          if (post) {
                            jobs_.post([this, mailbox, alive = alive_] {
                              if (*alive) deliver(mailbox);
                            });
                          }
                        };
                        reco::GrowSnapshot result =
                            reco::growRegions(cache_, parameters, options, [&](const reco::GrowSnapshot& snapshot) {
                              if (first_ms < 0.0) first_ms = snapshot.elapsed_ms;
                              publish(snapshot, false);
                            });
                        publish(result, true);
                      });
  return grow;
}

void GrowSession::deliver(const std::shared_ptr<Mailbox>& mailbox) {
  std::optional<GrowUpdate> update;
  {
    const std::scoped_lock lock(mailbox->mutex);
    update.swap(mailbox->pending);
  }
  if (!update || update->grow != current_) return;  // a cancelled grow's
  if (update->final) busy_ = false;
  on_update_(*update);
}

}  // namespace plumb::viewer
