// The viewer's grow session on the job system: snapshots arrive as continuations, coalesced,
// the final one last; a newer start cancels the older grow and its late snapshots are dropped.

#include "ui/viewer/grow_session.h"

#include <gtest/gtest.h>

#include <future>

#include "engine/lod/node_cache.h"
#include "engine/lod/octree.h"
#include "tests/support/generated_cloud.h"
#include "tests/support/temp_directory.h"

namespace plumb::viewer {
namespace {

// A floor and a wall meeting at x = 0:
//
//        z
//        |  wall (x = 0, y in [0, 2], z in [0, 1.5]), 2 cm grid
//        |
//        +------- x     floor (z = 0, x in [0, 2], y in [0, 2]), 1 cm by 2 cm grid
std::shared_ptr<const lod::Octree> buildFloorAndWall(const test::TempDirectory& dir) {
  lod::BuildOptions options;
  options.sources = {test::generatedSource(40'000, [](std::uint64_t i) {
    const double a = static_cast<double>((i / 2) % 200) / 100.0;
    const double b = static_cast<double>((i / 2) / 200 % 100) / 50.0;
    const Eigen::Vector3d p = i % 2 == 0 ? Eigen::Vector3d(a, b, 0.0) : Eigen::Vector3d(0.0, b, a * 0.75);
    return io::PointRecord{512000.0 + p.x(), 5403000.0 + p.y(), 250.0 + p.z(), {}, 0};
  })};
  options.output = dir.file("floor_wall.plumb");
  options.leaf_max_points = 5000;
  lod::buildOctree(options);
  return lod::Octree::open(options.output);
}

reco::GrowParameters parametersAt(const Eigen::Vector3d& seed) {
  reco::GrowParameters parameters{};
  parameters.seed = seed;
  parameters.seed_radius_m = 0.3;
  parameters.density = 1e4;
  parameters.spacing_m = 0.02;
  parameters.search_radius_m = 0.06;
  parameters.plane_threshold_m = 0.01;
  return parameters;
}

class GrowSessionTest : public ::testing::Test {
 protected:
  // Drains continuations, as the viewer's frames do, until the session's final update is in.
  void runToTheEnd(const GrowSession& session) {
    while (session.busy()) {
      jobs_.waitIdle();
      jobs_.drainContinuations();
    }
  }

  const test::TempDirectory dir_;
  lod::NodeCache cache_{buildFloorAndWall(dir_), 256 << 20};
  jobs::JobSystem jobs_;
};

TEST_F(GrowSessionTest, SnapshotsArriveOnTheMainThreadEndingWithTheFinalOne) {
  std::vector<GrowUpdate> updates;
  GrowSession session(jobs_, cache_, [&](const GrowUpdate& update) { updates.push_back(update); });
  const std::uint64_t grow = session.start(parametersAt({512000.2, 5403001.0, 250.2}));
  EXPECT_TRUE(session.busy());
  runToTheEnd(session);
  ASSERT_FALSE(updates.empty());
  for (const GrowUpdate& update : updates) EXPECT_EQ(update.grow, grow);
  EXPECT_TRUE(updates.back().final);
  EXPECT_TRUE(updates.back().snapshot.converged);
  EXPECT_EQ(updates.back().snapshot.segments.size(), 2u) << "the floor and the wall";
  EXPECT_GE(updates.back().first_progress_ms, 0.0);
}

TEST_F(GrowSessionTest, ANewerStartDropsTheOlderGrowsSnapshots) {
  std::vector<GrowUpdate> updates;
  GrowSession session(jobs_, cache_, [&](const GrowUpdate& update) { updates.push_back(update); });
  session.start(parametersAt({512000.2, 5403001.0, 250.2}));
  const std::uint64_t second = session.start(parametersAt({512001.5, 5403001.0, 250.0}));
  runToTheEnd(session);
  ASSERT_FALSE(updates.empty());
  for (const GrowUpdate& update : updates) EXPECT_EQ(update.grow, second) << "a stale snapshot got through";
  EXPECT_TRUE(updates.back().final);
}

// The only worker is held while the grow is started and cancelled, so its job runs with the cancel
// already set: the final update must say cancelled (a grow that ignored the cancel would converge).
TEST_F(GrowSessionTest, CancelEndsTheGrowWithACancelledFinalUpdate) {
  jobs::JobSystem one_worker(jobs::JobSystemOptions{1});
  std::promise<void> release;
  std::shared_future<void> released = release.get_future().share();
  one_worker.submit(jobs::Priority::interactive, "hold the worker", [released](const jobs::CancelToken&) {
    released.wait();
  });
  std::optional<GrowUpdate> last;
  GrowSession session(one_worker, cache_, [&](const GrowUpdate& update) { last = update; });
  session.start(parametersAt({512000.2, 5403001.0, 250.2}));
  session.cancel();
  release.set_value();
  while (session.busy()) {
    one_worker.waitIdle();
    one_worker.drainContinuations();
  }
  ASSERT_TRUE(last);
  EXPECT_TRUE(last->final);
  EXPECT_TRUE(last->snapshot.cancelled);
  EXPECT_FALSE(last->snapshot.converged);
}

}  // namespace
}  // namespace plumb::viewer
