// plumb simulate: a terrestrial laser scan of a built-in scene, with its ground truth.

#include <CLI/App.hpp>
#include <CLI/Config.hpp>
#include <CLI/Formatter.hpp>
#include <chrono>
#include <cstdio>
#include <memory>

#include "engine/core/atomic_file.h"
#include "engine/io/point_reader.h"
#include "engine/lod/octree_builder.h"
#include "reco/sim/scan_reader.h"
#include "reco/sim/scenes.h"
#include "reco/sim/simulation.h"
#include "ui/cli/arguments.h"
#include "ui/cli/build_report.h"
#include "ui/cli/command.h"
#include "ui/cli/progress_line.h"

namespace plumb::cli {
namespace {

struct SimulateOptions {
  reco::sim::SimulationRequest request;
  double noise_mm = 2.0;
  double points = 1e6;
  double step_deg = 0.0;
  std::string offset;
  std::size_t memory_mb = 2048;  // an octree output's build budget
};

// The scan built straight into an octree, as `plumb import` builds one from a file, scanning once
// per pass of the build instead of writing the points first: a billion-point scan needs no 33 GB
// of PLY. The octree and the truth appear together or not at all.
reco::sim::SimulationReport simulateIntoOctree(const SimulateOptions& options) {
  const reco::sim::SimulationRequest& request = options.request;
  reco::sim::PreparedScan prepared = reco::sim::prepareScan(request);
  prepared.source.counts = std::make_shared<reco::sim::ScanCounts>();
  const std::unique_ptr<AtomicFile> truth = reco::sim::openTruth(request);

  lod::BuildOptions build;
  const std::string name = prepared.report.scene + " scan";
  build.sources = {
      {name, [name, source = prepared.source] { return std::make_unique<reco::sim::ScanReader>(name, source); }}};
  build.output = request.points_path;
  build.memory_mb = options.memory_mb;
  ProgressLine progress("simulate");
  build.progress = [&](std::string_view phase, std::uint64_t done, std::uint64_t total) {
    progress.update(phase, done, total);
  };
  const auto start = std::chrono::steady_clock::now();
  const lod::BuildReport built = lod::buildOctree(build);
  progress.finish();

  reco::sim::SimulationReport report = prepared.report;
  report.counts = *prepared.source.counts;
  report.points_bytes = built.file_bytes;
  report.scan_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  reco::sim::commitTruthBeside(truth.get(), prepared, report, request.points_path);
  // The passes' times include the scans: each pass scanned again.
  printBuildReport(built, options.memory_mb);
  return report;
}

bool isOctreePath(const std::string& path) {
  return io::lowerExtension(path) == ".plumb";
}

void printReport(const reco::sim::SimulationRequest& request, const reco::sim::SimulationReport& report) {
  const auto& counts = report.counts;
  const auto& settings = request.scanner;
  const double seconds = report.pilot_seconds + report.scan_seconds;
  std::printf("simulated a %s scan from %zu station%s, seed %llu\n", report.scene.c_str(), report.stations.size(),
              report.stations.size() == 1 ? "" : "s", static_cast<unsigned long long>(settings.seed));
  std::printf("  pattern  %u x %u beams per station (%.4f x %.4f deg), max range %g m\n", report.pattern.columns,
              report.pattern.rows, report.pattern.azimuthStepDeg(), report.pattern.elevationStepDeg(),
              settings.max_range_m);
  std::printf("  noise    %g mm isotropic, +%g ppm of range, +%g urad angular; dropout %g\n", settings.noise_m * 1e3,
              settings.range_noise_ppm, settings.angular_noise_urad, settings.dropout);
  std::printf("  points   %s written; of %s beams %s found no surface within range and %s were dropped\n",
              withThousands(counts.returns).c_str(), withThousands(counts.rays).c_str(),
              withThousands(counts.misses).c_str(), withThousands(counts.dropped).c_str());
  const char* format = isOctreePath(request.points_path)                                                 ? "octree"
                       : reco::sim::pointsFormatOf(request.points_path) == reco::sim::PointsFormat::kLas ? "LAS 1.2"
                       : request.offset ? "PLY, double coordinates"
                                        : "PLY, float coordinates";
  std::printf("  output   %s (%s, %.1f MB", request.points_path.c_str(), format,
              static_cast<double>(report.points_bytes) / 1e6);
  if (request.offset) {
    std::printf(", offset %.3f %.3f %.3f", request.offset->x(), request.offset->y(), request.offset->z());
  }
  std::printf(")\n");
  if (!request.truth_path.empty()) {
    std::printf("  truth    %s (%zu planes, %zu corners, %zu edges)\n", request.truth_path.c_str(), report.planes,
                report.corners, report.edges);
  }
  std::printf("  time     %.2f s (pattern %.2f s, scan and write %.2f s): %.1f million points per second\n", seconds,
              report.pilot_seconds, report.scan_seconds,
              static_cast<double>(counts.returns) / std::max(seconds, 1e-9) / 1e6);
}

}  // namespace

Command addSimulateCommand(CLI::App& plumb) {
  auto options = std::make_shared<SimulateOptions>();
  auto& request = options->request;
  CLI::App* sub = plumb.add_subcommand(
      "simulate", "Simulate a terrestrial laser scan of a built-in scene and write it with its ground truth");
  sub->footer(
      "Scenes: room (7 x 5 x 2.5 m with furniture), office (three offices and a corridor), stairs (a staircase\n"
      "between two floors), facade (a building front with recessed windows, a door and a balcony).\n"
      "Example: plumb simulate --scene room --noise-mm 2 --points 1000000 --seed 1 \\\n"
      "           --offset 512000,5403000,250 -o room.ply --truth room.json");
  sub->add_option("--scene", request.scene, "Scene to scan")
      ->check(CLI::IsMember(reco::sim::sceneNames()))
      ->capture_default_str();
  auto* points = sub->add_option("--points", options->points,
                                 "Target number of points (the angular step is derived from it; within 1 %)")
                     ->check(finiteIn(1, static_cast<double>(reco::sim::kMaxSimulatedPoints)))
                     ->capture_default_str();
  sub->add_option("--step-deg", options->step_deg, "Angular step in degrees instead of a target point count")
      ->check(finiteIn(0.001, 10))
      ->excludes(points);
  sub->add_option("--noise-mm", options->noise_mm, "Isotropic 1-sigma point noise in millimetres")
      ->check(finiteIn(0, 1000))
      ->capture_default_str();
  sub->add_option("--range-noise-ppm", request.scanner.range_noise_ppm,
                  "Additional range noise proportional to the range, in parts per million")
      ->check(finiteIn(0, 1e5))
      ->capture_default_str();
  sub->add_option("--angular-noise-urad", request.scanner.angular_noise_urad,
                  "Additional angular noise in microradians")
      ->check(finiteIn(0, 1e5))
      ->capture_default_str();
  sub->add_option("--max-range", request.scanner.max_range_m, "Maximum range in metres")
      ->check(finiteIn(0.1, 10000))
      ->capture_default_str();
  sub->add_option("--dropout", request.scanner.dropout, "Probability that a return is lost")
      ->check(finiteIn(0, 0.99))
      ->capture_default_str();
  sub->add_option("--stations", request.station_count, "Number of scanner stations (default: the scene's)")
      ->check(CLI::Range(1, 255));
  sub->add_option("--rotate-deg", request.scanner.rotation_deg, "Rotate the scene about the vertical, in degrees")
      ->check(finiteIn(-360, 360))
      ->capture_default_str();
  sub->add_option("--seed", request.scanner.seed, "Random seed; the same seed gives the same scan")
      ->capture_default_str();
  sub->add_option("--offset", options->offset,
                  "X,Y,Z added to every coordinate (e.g. UTM); coordinates are then written as doubles");
  sub->add_option("-o,--output", request.points_path,
                  "Output: a binary PLY, a LAS 1.2 file (.las) or an octree (.plumb, built as plumb import builds one, "
                  "without writing the points first)")
      ->required();
  sub->add_option("--memory-mb", options->memory_mb, "An octree output's memory budget in MiB, as plumb import's")
      ->check(CLI::Range(64, 1 << 20))
      ->capture_default_str();
  sub->add_option("--truth", request.truth_path, "Output ground truth (JSON: planes, corners, edges)");

  auto run = [options]() -> int {
    auto& r = options->request;
    r.scanner.noise_m = options->noise_mm * 1e-3;
    if (!options->offset.empty()) r.offset = parseVector3(options->offset, "--offset");
    if (options->step_deg > 0.0) {
      r.scanner.pattern = reco::sim::ScanPattern::fromStep(options->step_deg);
    } else {
      r.target_points = static_cast<std::uint64_t>(std::llround(options->points));
    }
    if (isOctreePath(r.points_path)) {
      const reco::sim::SimulationReport report = simulateIntoOctree(*options);
      printReport(r, report);
      return 0;
    }
    ProgressLine progress("simulate");
    const reco::sim::SimulationReport report = reco::sim::simulate(r, [&](double f) { progress.update(f); });
    progress.finish();
    printReport(r, report);
    return 0;
  };
  return {sub, run};
}

}  // namespace plumb::cli
