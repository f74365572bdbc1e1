// Region growing speed (docs/benchmarks.md). Prints, asserts nothing.
//
//   plumb_bench_grow DIR   simulates the hall at 10 and 100 million points in DIR, builds their
//                          octrees, and clicks the middle of its 6 x 3 m wall y = 0 from 3 m
//                          (medium detail): time to the first snapshot and to convergence with
//                          an empty node cache (cold) and again with the nodes cached (warm)

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <string>

#include "engine/lod/node_cache.h"
#include "engine/lod/octree_builder.h"
#include "reco/region_grower.h"
#include "reco/sim/simulation.h"

namespace {

using namespace plumb;

// One grow, its times printed under `label` (null: silent).
void growOnce(lod::NodeCache& cache, const reco::GrowParameters& parameters, const char* label) {
  double first_ms = -1.0;
  const reco::GrowSnapshot result = reco::growRegions(cache, parameters, {}, [&](const reco::GrowSnapshot& s) {
    if (first_ms < 0.0) first_ms = s.elapsed_ms;
  });
  if (label == nullptr) return;
  std::uint64_t points = 0;
  for (const auto& segment : result.segments) points += segment.points;
  std::printf("  %s: first snapshot %.2f ms, converged %.2f ms; %zu segments, %llu points, level %u, %llu cells\n",
              label, first_ms, result.elapsed_ms, result.segments.size(), static_cast<unsigned long long>(points),
              result.level, static_cast<unsigned long long>(result.cells_visited));
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: plumb_bench_grow DIRECTORY\n");
    return 2;
  }
  const std::filesystem::path directory = argv[1];
  const Eigen::Vector3d offset(512000, 5403000, 250);
  // The middle of the hall's y = 0 wall (6 m long, 3 m high), in world coordinates.
  const Eigen::Vector3d click = offset + Eigen::Vector3d(3.0, 0.0, 1.5);
  for (const std::uint64_t points : {10'000'000ull, 100'000'000ull}) {
    reco::sim::SimulationRequest request;
    request.scene = "hall";
    request.target_points = points;
    request.offset = offset;
    request.ply_path = (directory / "hall.ply").string();
    reco::sim::simulate(request);
    lod::BuildOptions build;
    build.sources = lod::fileSources({request.ply_path});
    build.output = (directory / "hall.plumb").string();
    const lod::BuildReport report = lod::buildOctree(build);
    std::filesystem::remove(request.ply_path);

    const auto octree = lod::Octree::open(build.output);
    const reco::GrowParameters parameters = reco::parametersForView(reco::viewFromDistance(click, 3.0));
    std::printf(
        "hall, %llu points (%llu nodes), click on the middle of the 6 x 3 m wall from 3 m "
        "(r_s %.2f m, spacing %.3f m):\n",
        static_cast<unsigned long long>(report.points), static_cast<unsigned long long>(report.nodes),
        parameters.seed_radius_m, parameters.spacing_m);
    {
      // The process's first grow pays one-time costs (thread pool, allocator, page tables) that a
      // viewer pays at start-up: a grow on a cache of its own takes them first.
      lod::NodeCache warm_up(octree, std::size_t{1} << 30);
      growOnce(warm_up, parameters, nullptr);
    }
    lod::NodeCache cache(octree, std::size_t{1} << 30);  // cold: no node loaded yet
    growOnce(cache, parameters, "cold");
    growOnce(cache, parameters, "warm");
    std::filesystem::remove(build.output);
  }
  return 0;
}
