#include "reco/sim/scan_reader.h"

#include <tbb/task_arena.h>

#include <algorithm>

namespace plumb::reco::sim {
namespace {

// Blocks waiting in the queue: enough to keep the reader fed, few enough to bound the memory
// (a scanner block is a few thousand points).
constexpr std::size_t kQueuedBlocks = 16;

// Thrown by the sink to end a scan nobody reads any more.
struct ScanStopped {};

}  // namespace

ScanReader::ScanReader(std::string name, ScanSource source)
    : io::PointReader(std::move(name)), source_(std::move(source)) {
  info_.format = "simulated scan";
  info_.attributes.colour = true;
  info_.attributes.intensity = true;
}

ScanReader::~ScanReader() {
  if (!thread_.joinable()) return;  // never read: the scan never started
  {
    const std::lock_guard lock(mutex_);
    stop_ = true;
  }
  changed_.notify_all();
  thread_.join();
}

void ScanReader::produce() {
  try {
    // An arena of its own: a thread of the builder's pipeline waiting in read() must never pick
    // up a scanner task whose sink waits for that very read.
    tbb::task_arena arena;
    arena.execute([&] {
      const ScanCounts counts =
          scan(*source_.scene, source_.stations, source_.settings, [&](std::span<const ScanPoint> points) {
            std::vector<io::PointRecord> block;
            block.reserve(points.size());
            for (const ScanPoint& point : points) {
              const Eigen::Vector3d world = point.position + source_.offset;
              block.push_back(
                  {world.x(),
                   world.y(),
                   world.z(),
                   {io::widenColour(point.rgb[0]), io::widenColour(point.rgb[1]), io::widenColour(point.rgb[2])},
                   point.intensity});
            }
            std::unique_lock lock(mutex_);
            changed_.wait(lock, [&] { return stop_ || blocks_.size() < kQueuedBlocks; });
            if (stop_) throw ScanStopped{};
            blocks_.push_back(std::move(block));
            lock.unlock();
            changed_.notify_all();
          });
      if (source_.counts) *source_.counts = counts;
    });
  } catch (const ScanStopped&) {
  } catch (...) {
    const std::lock_guard lock(mutex_);
    error_ = std::current_exception();
  }
  {
    const std::lock_guard lock(mutex_);
    scanned_ = true;
  }
  changed_.notify_all();
}

bool ScanReader::read(io::PointBatch& batch, std::size_t max_points) {
  // The scan starts with the first read: a reader opened for its header alone costs nothing.
  if (!thread_.joinable()) thread_ = std::thread([this] { produce(); });
  batch.clear();
  while (batch.size() < max_points) {
    if (taken_ == current_.size()) {
      std::unique_lock lock(mutex_);
      changed_.wait(lock, [&] { return !blocks_.empty() || scanned_; });
      if (error_) std::rethrow_exception(error_);
      if (blocks_.empty()) break;  // scanned, and every block read
      current_ = std::move(blocks_.front());
      blocks_.pop_front();
      taken_ = 0;
      lock.unlock();
      changed_.notify_all();
    }
    const std::size_t n = std::min(max_points - batch.size(), current_.size() - taken_);
    for (std::size_t i = 0; i < n; ++i) deliver(batch, current_[taken_ + i]);
    taken_ += n;
  }
  return !batch.empty();
}

}  // namespace plumb::reco::sim
