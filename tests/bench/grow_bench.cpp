// Region growing speed (docs/benchmarks.md). Prints, asserts nothing.
//
//   plumb_bench_grow DIR   simulates the hall at 10 and 100 million points in DIR, builds their
//                          octrees, and clicks the middle of its 6 x 3 m wall y = 0 from 3 m
//                          (medium detail): time to the first snapshot and to convergence with
//                          an empty node cache (cold) and again with the nodes cached (warm);
//                          then simulates the room (5 mm noise) at 1, 10 and 100 million points
//                          and clicks 0.1 m inside its corner (0, 0, 0) at high and at full
//                          detail (t_p 15 mm): the same times, and the time per grown point
//   plumb_bench_grow DIR --detail-only   the room part alone

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>

#include "engine/core/huge_pages.h"
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
  std::printf(
      "  %s: first snapshot %.2f ms, converged %.2f ms (%.2f us a grown point); %zu segments, %zu corners, %llu "
      "points, level %u, %llu cells\n",
      label, first_ms, result.elapsed_ms,
      1000.0 * result.elapsed_ms / static_cast<double>(std::max<std::uint64_t>(points, 1)), result.segments.size(),
      result.corners.size(), static_cast<unsigned long long>(points), result.level,
      static_cast<unsigned long long>(result.cells_visited));
}

// Simulates `scene` with `points` by `scanner` into `directory` and builds its octree; returns
// its path.
std::string buildScene(const std::filesystem::path& directory, const char* scene, std::uint64_t points,
                       const reco::sim::ScannerSettings& scanner, const Eigen::Vector3d& offset,
                       lod::BuildReport& report) {
  reco::sim::SimulationRequest request;
  request.scene = scene;
  request.scanner = scanner;
  request.target_points = points;
  request.offset = offset;
  request.points_path = (directory / (std::string(scene) + ".ply")).string();
  reco::sim::simulate(request);
  lod::BuildOptions build;
  build.sources = lod::fileSources({request.points_path});
  build.output = (directory / (std::string(scene) + ".plumb")).string();
  report = lod::buildOctree(build);
  std::filesystem::remove(request.points_path);
  return build.output;
}

// The same click twice on a cache of `cache_bytes`: with no node loaded (cold), then on the
// nodes it loaded (warm). The process's first grow pays one-time costs (thread pool, allocator,
// page tables) that a viewer pays at start-up: a grow on a cache of its own takes them first.
void growColdAndWarm(const std::shared_ptr<const lod::Octree>& octree, const reco::GrowParameters& parameters,
                     std::size_t cache_bytes) {
  {
    lod::NodeCache warm_up(octree, cache_bytes);
    growOnce(warm_up, parameters, nullptr);
  }
  lod::NodeCache cache(octree, cache_bytes);
  growOnce(cache, parameters, "cold");
  growOnce(cache, parameters, "warm");
  std::fflush(stdout);
}

// High and full detail at a room corner, cold and warm, at 1, 10 and 100 million points.
void benchDetail(const std::filesystem::path& directory) {
  const Eigen::Vector3d offset(512000, 5403000, 250);
  const Eigen::Vector3d click = offset + Eigen::Vector3d(0.1, 0.1, 0.1);
  for (const std::uint64_t points : {1'000'000ull, 10'000'000ull, 100'000'000ull}) {
    reco::sim::ScannerSettings scanner;
    scanner.noise_m = 0.005;
    scanner.seed = 11;
    lod::BuildReport report;
    const std::string path = buildScene(directory, "room", points, scanner, offset, report);
    const auto octree = lod::Octree::open(path);
    const reco::ParameterConstants constants{.plane_threshold_m = 0.015};
    const double seed_radius = reco::parametersForView(reco::viewFromDistance(click, 3.0), constants).seed_radius_m;
    for (const reco::Detail detail : {reco::Detail::kHigh, reco::Detail::kFull}) {
      const double full_density = std::pow(octree->spacing(octree->header().depth), -3.0);
      const reco::GrowParameters parameters = reco::parametersForDensity(
          click, reco::densityForDetail(detail, constants, full_density), seed_radius, constants);
      std::printf("room, 5 mm noise, %llu points (%llu nodes), click 0.1 m inside corner (0, 0, 0), %s detail:\n",
                  static_cast<unsigned long long>(report.points), static_cast<unsigned long long>(report.nodes),
                  detail == reco::Detail::kFull ? "full" : "high");
      growColdAndWarm(octree, parameters, std::size_t{4} << 30);
    }
    std::filesystem::remove(path);
  }
}

}  // namespace

int main(int argc, char** argv) {
  plumb::runWithHugePageHeap(argv);  // as plumb runs
  const bool detail_only = argc == 3 && std::strcmp(argv[2], "--detail-only") == 0;
  if (argc != 2 && !detail_only) {
    std::fprintf(stderr, "usage: plumb_bench_grow DIRECTORY [--detail-only]\n");
    return 2;
  }
  const std::filesystem::path directory = argv[1];
  if (detail_only) {
    benchDetail(directory);
    return 0;
  }
  const Eigen::Vector3d offset(512000, 5403000, 250);
  // The middle of the hall's y = 0 wall (6 m long, 3 m high), in world coordinates.
  const Eigen::Vector3d click = offset + Eigen::Vector3d(3.0, 0.0, 1.5);
  for (const std::uint64_t points : {10'000'000ull, 100'000'000ull}) {
    lod::BuildReport report;
    const std::string path = buildScene(directory, "hall", points, reco::sim::ScannerSettings{}, offset, report);
    const auto octree = lod::Octree::open(path);
    const reco::GrowParameters parameters = reco::parametersForView(reco::viewFromDistance(click, 3.0));
    std::printf(
        "hall, %llu points (%llu nodes), click on the middle of the 6 x 3 m wall from 3 m "
        "(r_s %.2f m, spacing %.3f m):\n",
        static_cast<unsigned long long>(report.points), static_cast<unsigned long long>(report.nodes),
        parameters.seed_radius_m, parameters.spacing_m);
    growColdAndWarm(octree, parameters, std::size_t{1} << 30);
    std::filesystem::remove(path);
  }
  benchDetail(directory);
  return 0;
}
