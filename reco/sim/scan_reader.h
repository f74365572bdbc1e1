#pragma once
// A simulated scan read as a point file, so that `plumb simulate -o X.plumb` builds an octree
// from a scan of any size without writing the scan first (a billion points would be 33 GB of
// PLY). From the first read, the scanner runs on a thread of its own, in a oneTBB arena of its own, and hands its
// blocks over through a queue of a few blocks. Each reader scans anew and delivers the same
// points in the same order (the scanner is deterministic for a seed), so the octree builder
// reads it once per pass as it reads a file.

#include <condition_variable>
#include <deque>
#include <exception>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

#include "engine/io/point_reader.h"
#include "reco/sim/scanner.h"

namespace plumb::reco::sim {

struct ScanSource {
  std::shared_ptr<const Scene> scene;
  std::vector<Eigen::Vector3d> stations;  // scene-local
  ScannerSettings settings;
  Eigen::Vector3d offset = Eigen::Vector3d::Zero();  // added to every point
  // Where a reader whose scan ran to its end leaves the scan's counts, when set.
  std::shared_ptr<ScanCounts> counts;
};

class ScanReader final : public io::PointReader {
 public:
  // `name` names the scan in messages ("office scan").
  ScanReader(std::string name, ScanSource source);
  // Stops the scan (a build that failed or ended early) and waits for its thread.
  ~ScanReader() override;
  ScanReader(const ScanReader&) = delete;
  ScanReader& operator=(const ScanReader&) = delete;

  bool read(io::PointBatch& batch, std::size_t max_points) override;

 private:
  void produce();

  ScanSource source_;
  std::mutex mutex_;
  std::condition_variable changed_;
  std::deque<std::vector<io::PointRecord>> blocks_;
  bool scanned_ = false;  // the scan has delivered its last block (or failed)
  bool stop_ = false;
  std::exception_ptr error_;
  std::vector<io::PointRecord> current_;  // the block being read
  std::size_t taken_ = 0;                 // of current_
  std::thread thread_;
};

}  // namespace plumb::reco::sim
