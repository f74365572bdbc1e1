// Throughput of the scanner simulator and of the plane regression. Figures only; see
// docs/benchmarks.md for the recorded runs.
//
//   Scan/<scene>/<points>:      casting, noise and attributes, points handed to a counting sink
//   Simulate/<scene>/<points>:  `plumb simulate` end to end: pattern, scan, binary PLY, fsync
//   RegressionAdd:              PlaneRegression::add per point

#include <benchmark/benchmark.h>
#include <unistd.h>

#include <filesystem>

#include "engine/core/random.h"
#include "reco/plane_regression.h"
#include "reco/sim/scenes.h"
#include "reco/sim/simulation.h"

namespace {

using namespace plumb::reco;

std::vector<Eigen::Vector3d> defaultStations(const sim::Scene& scene) {
  return {scene.stations.begin(), scene.stations.begin() + static_cast<std::ptrdiff_t>(scene.default_station_count)};
}

void scanBenchmark(benchmark::State& state, const std::string& scene_name, std::uint64_t target) {
  const sim::Scene scene = sim::makeScene(scene_name);
  const auto stations = defaultStations(scene);
  sim::ScannerSettings settings;
  settings.pattern = sim::patternForTarget(scene, stations, settings, target);
  std::uint64_t points = 0;
  for (auto _ : state) {
    const sim::ScanCounts counts = sim::scan(scene, stations, settings, [](std::span<const sim::ScanPoint> block) {
      benchmark::DoNotOptimize(block.data());
    });
    points += counts.returns;
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(points));
}

void simulateBenchmark(benchmark::State& state, const std::string& scene_name, std::uint64_t target) {
  const std::filesystem::path path =
      std::filesystem::temp_directory_path() / ("plumb_bench_" + std::to_string(::getpid()) + ".ply");
  sim::SimulationRequest request;
  request.scene = scene_name;
  request.target_points = target;
  request.offset = Eigen::Vector3d(512000, 5403000, 250);
  request.points_path = path.string();
  std::uint64_t points = 0;
  for (auto _ : state) points += sim::simulate(request).counts.returns;
  state.SetItemsProcessed(static_cast<std::int64_t>(points));
  std::filesystem::remove(path);
}

void regressionAddBenchmark(benchmark::State& state) {
  plumb::Random random(1);
  std::vector<Eigen::Vector3d> points(1 << 16);
  for (auto& p : points) p = Eigen::Vector3d(512000 + random.uniform(), 5403000 + random.uniform(), 250);
  for (auto _ : state) {
    PlaneRegression regression;
    for (const auto& p : points) regression.add(p);
    benchmark::DoNotOptimize(regression);
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(points.size()));
}

const bool registered = [] {
  for (const std::string& scene : sim::sceneNames()) {
    for (std::uint64_t target : {20'000ull, 1'000'000ull, 10'000'000ull}) {
      benchmark::RegisterBenchmark(("Scan/" + scene + "/" + std::to_string(target)).c_str(), scanBenchmark, scene,
                                   target)
          ->Unit(benchmark::kMillisecond)
          ->UseRealTime();
    }
  }
  for (std::uint64_t target : {1'000'000ull, 10'000'000ull}) {
    benchmark::RegisterBenchmark(("Simulate/room/" + std::to_string(target)).c_str(), simulateBenchmark, "room", target)
        ->Unit(benchmark::kMillisecond)
        ->UseRealTime();
  }
  benchmark::RegisterBenchmark("RegressionAdd", regressionAddBenchmark);
  return true;
}();

}  // namespace

BENCHMARK_MAIN();
