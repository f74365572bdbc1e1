// Octree query figures (docs/benchmarks.md). Prints, asserts nothing.
//
//   plumb_bench_lod query OCTREE...   latency of a 1 m sphere query at the finest level, from
//                                     an empty node cache (cold) and again (warm)
//   plumb_bench_lod locality DIR      builds two floors of equal density, 1 and 100 million
//                                     points, in DIR and compares the nodes one local query
//                                     touches in each

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <string>
#include <vector>

#include "engine/core/huge_pages.h"
#include "engine/core/random.h"
#include "engine/lod/lod_query.h"
#include "engine/lod/node_cache.h"
#include "engine/lod/octree_builder.h"
#include "tests/support/generated_cloud.h"

namespace {

using namespace plumb;
using Clock = std::chrono::steady_clock;

struct QueryResult {
  double milliseconds;
  std::size_t nodes;
  std::uint64_t visited;
  std::size_t points;
};

// Everything the region grower will ask at its start: the nodes of the sphere, their points
// (through the cache), and which points lie inside.
QueryResult sphereQuery(lod::NodeCache& cache, const std::array<double, 3>& centre, double radius,
                        std::uint32_t level) {
  const auto start = Clock::now();
  lod::QueryStats stats;
  const auto nodes = lod::nodesInSphere(cache.octree(), centre, radius, level, &stats);
  std::size_t inside = 0;
  for (const lod::NodeInfo* node : nodes) {
    const auto points = cache.get(node->key);
    for (std::size_t i = 0; i < points->size(); ++i) {
      const auto p = points->position(i);
      const double dx = p[0] - centre[0], dy = p[1] - centre[1], dz = p[2] - centre[2];
      if (dx * dx + dy * dy + dz * dz <= radius * radius) ++inside;
    }
  }
  return {std::chrono::duration<double, std::milli>(Clock::now() - start).count(), nodes.size(), stats.nodes_visited,
          inside};
}

// Query centres on the cloud: points of randomly chosen leaves.
std::vector<std::array<double, 3>> queryCentres(const lod::Octree& octree, int count) {
  std::vector<const lod::NodeInfo*> leaves;
  for (const lod::NodeInfo& node : octree.nodes()) {
    if (node.child_mask == 0) leaves.push_back(&node);
  }
  Random random(7);
  std::vector<std::array<double, 3>> centres;
  for (int i = 0; i < count; ++i) {
    const lod::NodeInfo& leaf = *leaves[random.below(leaves.size())];
    const lod::NodePoints points = octree.load(leaf);
    centres.push_back(points.position(random.below(points.size())));
  }
  return centres;
}

double percentile(std::vector<double> values, double q) {
  std::sort(values.begin(), values.end());
  return values[static_cast<std::size_t>(q * static_cast<double>(values.size() - 1))];
}

void queryBenchmark(const std::string& path) {
  const auto octree = lod::Octree::open(path);
  const auto centres = queryCentres(*octree, 50);
  const std::uint32_t finest = octree->header().depth;
  std::vector<double> cold, warm;
  std::size_t nodes = 0, points = 0;
  lod::NodeCache warm_cache(octree, std::size_t{512} << 20);
  for (const auto& centre : centres) {
    lod::NodeCache empty(octree, std::size_t{512} << 20);
    const QueryResult first = sphereQuery(empty, centre, 1.0, finest);
    cold.push_back(first.milliseconds);
    nodes += first.nodes;
    points += first.points;
    sphereQuery(warm_cache, centre, 1.0, finest);
  }
  for (const auto& centre : centres) warm.push_back(sphereQuery(warm_cache, centre, 1.0, finest).milliseconds);
  std::printf("%s: %llu points, depth %u; 1 m sphere at the finest level (spacing %.4f m), %zu queries:\n",
              path.c_str(), static_cast<unsigned long long>(octree->header().point_count), finest,
              octree->spacing(finest), centres.size());
  std::printf("  %.1f nodes and %.0f points per query\n", static_cast<double>(nodes) / static_cast<double>(centres.size()),
              static_cast<double>(points) / static_cast<double>(centres.size()));
  std::printf("  cold (empty node cache, file in the OS page cache): median %.2f ms, 95th percentile %.2f ms\n",
              percentile(cold, 0.5), percentile(cold, 0.95));
  std::printf("  warm (nodes cached):                                 median %.2f ms, 95th percentile %.2f ms\n",
              percentile(warm, 0.5), percentile(warm, 0.95));
}

std::shared_ptr<const lod::Octree> buildFloor(const std::string& path, double side) {
  const auto count = static_cast<std::uint64_t>(side * side * 100.0);  // 100 points per m^2
  lod::BuildOptions options;
  options.sources = {test::generatedSource(count, [side](std::uint64_t i) {
    return io::PointRecord{512000.0 + side * test::unitHash(i, 1), 5403000.0 + side * test::unitHash(i, 2),
                           250.0 + 0.002 * test::unitHash(i, 3), {0, 0, 0}, 0};
  })};
  options.output = path;
  const auto start = Clock::now();
  const lod::BuildReport report = lod::buildOctree(options);
  std::printf("built %s: %llu points, %llu nodes in %.1f s\n", path.c_str(), static_cast<unsigned long long>(report.points),
              static_cast<unsigned long long>(report.nodes),
              std::chrono::duration<double>(Clock::now() - start).count());
  return lod::Octree::open(path);
}

void localityBenchmark(const std::string& directory) {
  const auto small = buildFloor(directory + "/floor_1m.plumb", 100.0);
  const auto large = buildFloor(directory + "/floor_100m.plumb", 1000.0);
  const std::array<double, 3> centre{512050.0, 5403050.0, 250.0};
  for (const auto& octree : {small, large}) {
    lod::NodeCache cache(octree, std::size_t{256} << 20);
    const std::uint32_t level = octree->levelForSpacing(0.1);
    const QueryResult result = sphereQuery(cache, centre, 1.0, level);
    std::printf("%llu points, %zu nodes: 1 m query at spacing 0.1 m (level %u): %llu nodes visited, %zu loaded, "
                "%zu points, %.2f ms cold\n",
                static_cast<unsigned long long>(octree->header().point_count), octree->nodes().size(), level,
                static_cast<unsigned long long>(result.visited), result.nodes, result.points, result.milliseconds);
  }
}

}  // namespace

int main(int argc, char** argv) {
  plumb::runWithHugePageHeap(argv);  // as plumb runs
  const std::vector<std::string> args(argv + 1, argv + argc);
  if (args.size() >= 2 && args[0] == "query") {
    for (std::size_t i = 1; i < args.size(); ++i) queryBenchmark(args[i]);
    return 0;
  }
  if (args.size() == 2 && args[0] == "locality") {
    localityBenchmark(args[1]);
    return 0;
  }
  std::fprintf(stderr, "usage: plumb_bench_lod query OCTREE... | plumb_bench_lod locality DIRECTORY\n");
  return 2;
}
