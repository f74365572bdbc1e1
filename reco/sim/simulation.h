#pragma once
// `plumb simulate` as a library call: scan a scene and write the points (binary PLY) and the
// ground truth (JSON, docs/simulator.md). Both files appear atomically and together; on any
// error neither is left behind.

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "reco/sim/scanner.h"

namespace plumb::reco::sim {

struct SimulationRequest {
  std::string scene = "room";
  ScannerSettings scanner;
  // Either a target point count (the pattern is derived from it) or scanner.pattern as given.
  std::optional<std::uint64_t> target_points;
  // How many of the scene's stations to use; 0 means the scene's default.
  std::size_t station_count = 0;
  // Added to every output coordinate; when set, coordinates are written as doubles.
  std::optional<Eigen::Vector3d> offset;
  std::string ply_path;
  std::string truth_path;  // empty: no ground truth file
};

struct SimulationReport {
  std::string scene;
  std::vector<Eigen::Vector3d> stations;  // world coordinates, offset included
  ScanPattern pattern;
  ScanCounts counts;
  std::uint64_t ply_bytes = 0;
  std::size_t planes = 0, corners = 0, edges = 0;
  double pilot_seconds = 0.0;  // deriving the pattern from the target
  double scan_seconds = 0.0;   // casting, noise and writing
};

// The largest point count a request may ask for.
constexpr std::uint64_t kMaxSimulatedPoints = 20'000'000'000;

// Runs the request. Throws plumb::Error for requests that cannot be met (unknown scene, too many
// stations, not enough disk space, unwritable output). `progress` receives the fraction done.
SimulationReport simulate(const SimulationRequest& request, const std::function<void(double)>& progress = {});

}  // namespace plumb::reco::sim
