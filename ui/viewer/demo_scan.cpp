#include "ui/viewer/demo_scan.h"

#include <unistd.h>

#include <cstdlib>
#include <system_error>

#include "engine/core/error.h"
#include "engine/lod/octree_builder.h"
#include "reco/sim/simulation.h"

namespace plumb::viewer {
namespace {

// Where the demo lies in the world: UTM-like coordinates, as a real survey's are, so the demo
// exercises the double-precision path.
const Eigen::Vector3d kOffset(512000.0, 5403000.0, 250.0);
constexpr std::uint64_t kDemoPoints = 1'000'000;
constexpr double kDemoNoiseM = 0.002;
// The name carries what makes the scan, so a changed demo is generated anew.
constexpr const char* kDemoName = "demo-office-1M-2mm-v1";

}  // namespace

std::filesystem::path userCacheDirectory() {
  std::filesystem::path base;
  if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg != nullptr && xdg[0] == '/') {
    base = xdg;
  } else if (const char* home = std::getenv("HOME"); home != nullptr && home[0] != '\0') {
    base = std::filesystem::path(home) / ".cache";
  } else {
    throw Error("no cache directory: set HOME or XDG_CACHE_HOME");
  }
  const std::filesystem::path directory = base / "plumb";
  std::error_code error;
  std::filesystem::create_directories(directory, error);
  if (error) throw Error(directory.string() + ": cannot create the cache directory: " + error.message());
  return directory;
}

DemoScan ensureDemoScan(const std::function<void(std::string_view, double)>& progress) {
  const std::filesystem::path directory = userCacheDirectory();
  DemoScan demo;
  demo.octree = directory / (std::string(kDemoName) + ".plumb");
  demo.truth = directory / (std::string(kDemoName) + ".truth.json");
  demo.home.position = kOffset + Eigen::Vector3d(0.8, 1.0, 1.6);
  demo.home.target = kOffset + Eigen::Vector3d(6.0, 1.0, 1.2);
  if (std::filesystem::exists(demo.octree) && std::filesystem::exists(demo.truth)) return demo;

  // The scan goes to a process-private PLY, removed once indexed; the truth and the octree
  // appear atomically, the octree last, so its presence means the demo is complete.
  const std::filesystem::path ply = directory / (std::string(kDemoName) + "." + std::to_string(::getpid()) + ".ply");
  reco::sim::SimulationRequest request;
  request.scene = "office";
  request.scanner.noise_m = kDemoNoiseM;
  request.scanner.seed = 1;
  request.target_points = kDemoPoints;
  request.offset = kOffset;
  request.points_path = ply.string();
  request.truth_path = demo.truth.string();
  try {
    reco::sim::simulate(request, [&](double fraction) {
      if (progress) progress("simulating the demo office scan", fraction);
    });
    lod::BuildOptions build;
    build.sources = lod::fileSources({ply.string()});
    build.output = demo.octree.string();
    build.progress = [&](std::string_view phase, std::uint64_t done, std::uint64_t total) {
      if (progress) progress(phase, total > 0 ? static_cast<double>(done) / static_cast<double>(total) : 0.0);
    };
    lod::buildOctree(build);
  } catch (...) {
    std::error_code ignored;
    std::filesystem::remove(ply, ignored);
    throw;
  }
  std::error_code ignored;
  std::filesystem::remove(ply, ignored);
  return demo;
}

}  // namespace plumb::viewer
