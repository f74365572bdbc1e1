#include "engine/lod/node_cache.h"

#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <fstream>
#include <thread>

#include "engine/core/error.h"
#include "engine/lod/octree_builder.h"
#include "tests/support/generated_cloud.h"
#include "tests/support/temp_directory.h"

namespace plumb::lod {
namespace {

// Built on the calling thread alone (an arena of one): these tests are about the cache's
// threads, and ThreadSanitizer cannot see the builder's oneTBB pipeline synchronise (Debian's
// libtbb is not instrumented), so its hand-overs would read as races.
std::string buildCloud(const test::TempDirectory& dir) {
  BuildOptions options;
  options.sources = {test::generatedSource(100'000, [](std::uint64_t i) {
    return test::withId(10.0 * test::unitHash(i, 1), 10.0 * test::unitHash(i, 2), 3.0 * test::unitHash(i, 3), i);
  })};
  options.output = dir.file("cloud.plumb");
  options.leaf_max_points = 1000;
  options.memory_mb = 128;
  options.threads = 1;
  tbb::task_arena(1).execute([&] { buildOctree(options); });
  return options.output;
}

TEST(NodeCache, HitsReturnTheSameDataAndMissesLoadOnce) {
  test::TempDirectory dir;
  NodeCache cache(Octree::open(buildCloud(dir)), 64 << 20);
  const auto first = cache.get(CellKey{});
  ASSERT_NE(first, nullptr);
  EXPECT_EQ(cache.get(CellKey{}), first);
  EXPECT_EQ(cache.stats().misses, 1u);
  EXPECT_EQ(cache.stats().hits, 1u);
  EXPECT_EQ(cache.get(CellKey{20, 1, 2, 3}), nullptr) << "no such node";
}

TEST(NodeCache, TheBudgetEvictsLeastRecentlyUsed) {
  test::TempDirectory dir;
  const auto octree = Octree::open(buildCloud(dir));
  const std::size_t budget = 200'000;  // a handful of nodes of 1000 points
  NodeCache cache(octree, budget);
  std::size_t largest = 0;
  for (const NodeInfo& node : octree->nodes()) {
    const auto points = cache.get(node.key);
    largest = std::max(largest, points->bytes());
    EXPECT_LE(cache.stats().bytes, budget + largest);
  }
  EXPECT_GT(cache.stats().evictions, 0u);
  // The most recent node stays.
  const auto last = octree->nodes().back().key;
  const auto misses = cache.stats().misses;
  cache.get(last);
  EXPECT_EQ(cache.stats().misses, misses);
}

// Four threads read every node three times through a cache too small to keep them all (loads,
// evictions and hits interleave); each must see exactly the points a direct load gives.
TEST(NodeCache, ConcurrentReadersSeeTheFileContents) {
  test::TempDirectory dir;
  const auto octree = Octree::open(buildCloud(dir));
  std::vector<NodePoints> expected;
  for (const NodeInfo& node : octree->nodes()) expected.push_back(octree->load(node));
  const auto same = [](const NodePoints& a, const NodePoints& b) {
    if (a.key != b.key || a.origin != b.origin || a.points.size() != b.points.size()) return false;
    for (std::size_t i = 0; i < a.points.size(); ++i) {
      const PackedPoint &p = a.points[i], &q = b.points[i];
      if (p.x != q.x || p.y != q.y || p.z != q.z || p.rgb != q.rgb || p.intensity != q.intensity) return false;
    }
    return true;
  };
  NodeCache cache(octree, 1 << 20);
  std::vector<std::thread> threads;
  std::atomic<int> mismatches{0};
  for (int t = 0; t < 4; ++t) {
    threads.emplace_back([&, t] {
      for (int round = 0; round < 3; ++round) {
        for (std::size_t i = static_cast<std::size_t>(t); i < octree->nodes().size(); i += 2) {
          const auto cached = cache.get(octree->nodes()[i].key);
          if (!cached || !same(*cached, expected[i])) ++mismatches;
        }
      }
    });
  }
  for (auto& thread : threads) thread.join();
  EXPECT_EQ(mismatches.load(), 0);
  EXPECT_GT(cache.stats().evictions, 0u) << "the budget must be too small for the cloud, or nothing interleaves";
}

TEST(NodeCache, BackgroundLoadsAreJoinedNotRepeated) {
  test::TempDirectory dir;
  const auto octree = Octree::open(buildCloud(dir));
  NodeCache cache(octree, 64 << 20);
  const CellKey key = octree->nodes().back().key;
  const auto early = cache.tryGet(key);  // starts the load in the background
  const auto points = cache.get(key);    // waits for that load, or finds it done
  ASSERT_NE(points, nullptr);
  EXPECT_EQ(cache.stats().misses, 1u);
  EXPECT_EQ(cache.tryGet(key), points);
  if (early) {
    EXPECT_EQ(early, points);
  }
}

TEST(NodeCache, ACorruptNodeIsAnErrorForEveryCaller) {
  test::TempDirectory dir;
  const std::string path = buildCloud(dir);
  std::string bytes = test::readFile(path);
  bytes[kHeaderBytes + 1] ^= 0x40;  // inside the first node block written
  std::ofstream(path, std::ios::binary | std::ios::trunc)
      .write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  const auto octree = Octree::open(path);
  NodeCache cache(octree, 64 << 20);
  int errors = 0;
  for (const NodeInfo& node : octree->nodes()) {
    try {
      cache.get(node.key);
    } catch (const Error&) {
      ++errors;
      EXPECT_THROW(cache.get(node.key), Error) << "a failed load must not be cached as success";
    }
  }
  EXPECT_EQ(errors, 1);
}

}  // namespace
}  // namespace plumb::lod
