#pragma once
// `plumb simulate` as a library call: scan a scene and write the points (binary PLY, or LAS 1.2
// for a path ending in .las) and the ground truth (JSON, docs/simulator.md). Both files appear
// atomically and together; on any error neither is left behind.

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "engine/core/atomic_file.h"
#include "reco/sim/scan_reader.h"
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
  std::string points_path;  // .las: LAS 1.2, point format 2 (the plane in the point source ID); else binary PLY
  std::string truth_path;   // empty: no ground truth file
};

struct SimulationReport {
  std::string scene;
  std::vector<Eigen::Vector3d> stations;  // world coordinates, offset included
  ScanPattern pattern;
  ScanCounts counts;
  std::uint64_t points_bytes = 0;
  std::size_t planes = 0, corners = 0, edges = 0;
  double pilot_seconds = 0.0;  // deriving the pattern from the target
  double scan_seconds = 0.0;   // casting, noise and writing
};

enum class PointsFormat { kPly, kLas };
// The format of a points file by its extension: .las (any case) is LAS, anything else PLY.
PointsFormat pointsFormatOf(const std::string& path);

// The largest point count a request may ask for.
constexpr std::uint64_t kMaxSimulatedPoints = 20'000'000'000;

// Runs the request. Throws plumb::Error for requests that cannot be met (unknown scene, too many
// stations, not enough disk space, unwritable output). `progress` receives the fraction done.
SimulationReport simulate(const SimulationRequest& request, const std::function<void(double)>& progress = {});

// The scan a request describes, ready to run: what simulate() scans, and what a ScanReader
// (scan_reader.h) scans once per pass of an octree build (`plumb simulate -o X.plumb`).
struct PreparedScan {
  ScanSource source;        // the scene, its stations, the settings with the pattern resolved, the offset
  SceneFrame frame;         // scene to world
  SimulationReport report;  // all but what the scan measures (counts, bytes, scan time)
};
// Throws plumb::Error as simulate() does for a request that cannot be met.
PreparedScan prepareScan(const SimulationRequest& request);

// The ground-truth file of a request (null when it asks for none), created at once so that an
// unwritable path fails before the scan; commitTruthBeside() writes it for the scan `report`
// describes and moves it into place once `points_path` is there, and removes that again when it
// cannot: both outputs or neither.
std::unique_ptr<AtomicFile> openTruth(const SimulationRequest& request);
void commitTruthBeside(AtomicFile* truth, const PreparedScan& prepared, const SimulationReport& report,
                       const std::string& points_path);

}  // namespace plumb::reco::sim
