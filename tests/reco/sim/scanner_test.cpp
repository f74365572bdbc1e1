#include "reco/sim/scanner.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cmath>

#include "reco/sim/scene_builder.h"
#include "reco/sim/scenes.h"

namespace plumb::reco::sim {
namespace {

std::vector<ScanPoint> collect(const Scene& scene, const ScannerSettings& settings, std::size_t stations = 1) {
  std::vector<ScanPoint> points;
  const std::vector<Eigen::Vector3d> used(scene.stations.begin(),
                                          scene.stations.begin() + static_cast<std::ptrdiff_t>(stations));
  scan(scene, used, settings,
       [&](std::span<const ScanPoint> block) { points.insert(points.end(), block.begin(), block.end()); });
  return points;
}

// RMS distance of the points to the true planes they were measured on (world frame).
double rmsToTruePlanes(const Scene& scene, const std::vector<ScanPoint>& points, double rotation_deg) {
  const SceneFrame frame{rotation_deg, Eigen::Vector3d::Zero()};
  std::vector<TruthPlane> world;
  for (const TruthPlane& plane : scene.planes) world.push_back(frame.toWorld(plane));
  double sum = 0.0;
  for (const ScanPoint& p : points) {
    const double d = world[p.plane].normal.dot(p.position) + world[p.plane].offset;
    sum += d * d;
  }
  return std::sqrt(sum / static_cast<double>(points.size()));
}

ScannerSettings settingsWith(double noise_m, double step_deg) {
  ScannerSettings settings;
  settings.noise_m = noise_m;
  settings.pattern = ScanPattern::fromStep(step_deg);
  return settings;
}

TEST(Scanner, NoiseFreePointsLieOnTheirPlanes) {
  const Scene scene = roomScene();
  const auto points = collect(scene, settingsWith(0.0, 0.5));
  ASSERT_GT(points.size(), 100'000u);
  EXPECT_LT(rmsToTruePlanes(scene, points, 0.0), 1e-9);
}

struct NoiseCase {
  std::string scene;
  double noise_m;
  double rotation_deg;
};

// Names the case in test listings (instead of a byte dump).
void PrintTo(const NoiseCase& c, std::ostream* out) {
  *out << c.scene << ", " << c.noise_m * 1e3 << " mm, rotated " << c.rotation_deg << " deg";
}

class ScannerNoise : public ::testing::TestWithParam<NoiseCase> {};

// The acceptance test of the simulator: the RMS distance of the points to their true planes is
// the requested noise (within 10 %), whatever the incidence angles of the scene.
TEST_P(ScannerNoise, RmsDistanceToTruePlanesIsTheRequestedNoise) {
  const NoiseCase& c = GetParam();
  const Scene scene = makeScene(c.scene);
  ScannerSettings settings = settingsWith(c.noise_m, 0.4);
  settings.rotation_deg = c.rotation_deg;
  const auto points = collect(scene, settings, scene.default_station_count);
  ASSERT_GT(points.size(), 100'000u);
  const double rms = rmsToTruePlanes(scene, points, c.rotation_deg);
  RecordProperty("rms_mm", std::to_string(rms * 1e3));
  EXPECT_NEAR(rms, c.noise_m, 0.1 * c.noise_m) << c.scene << ": rms " << rms * 1e3 << " mm";
}

INSTANTIATE_TEST_SUITE_P(Scenes, ScannerNoise,
                         ::testing::Values(NoiseCase{"room", 0.002, 0.0}, NoiseCase{"room", 0.001, 30.0},
                                           NoiseCase{"office", 0.010, 0.0}, NoiseCase{"stairs", 0.002, -45.0},
                                           NoiseCase{"facade", 0.005, 0.0}, NoiseCase{"room", 0.030, 10.0}),
                         [](const ::testing::TestParamInfo<NoiseCase>& param_info) {
                           const NoiseCase& c = param_info.param;
                           return c.scene + "_" + std::to_string(std::lround(c.noise_m * 1e3)) + "mm_rotated" +
                                  std::to_string(std::lround(std::abs(c.rotation_deg))) + "deg";
                         });

TEST(Scanner, SameSeedSameScanWhateverTheThreadCount) {
  const Scene scene = officeScene();
  ScannerSettings settings = settingsWith(0.002, 0.8);
  settings.dropout = 0.1;
  const auto parallel = collect(scene, settings, 2);
  std::vector<ScanPoint> serial;
  {
    tbb::global_control one_thread(tbb::global_control::max_allowed_parallelism, 1);
    serial = collect(scene, settings, 2);
  }
  ASSERT_EQ(parallel.size(), serial.size());
  for (std::size_t i = 0; i < parallel.size(); ++i) {
    ASSERT_EQ(parallel[i].position, serial[i].position) << i;
    ASSERT_EQ(parallel[i].rgb, serial[i].rgb);
    ASSERT_EQ(parallel[i].intensity, serial[i].intensity);
  }
  settings.seed = 2;
  const auto other = collect(scene, settings, 2);
  EXPECT_NE(other.front().position, parallel.front().position);
}

TEST(Scanner, CountsEveryBeam) {
  const Scene scene = facadeScene();  // beams into the sky find nothing
  ScannerSettings settings = settingsWith(0.002, 1.0);
  settings.dropout = 0.25;
  std::uint64_t delivered = 0;
  const ScanCounts counts =
      scan(scene, {scene.stations[0]}, settings, [&](std::span<const ScanPoint> block) { delivered += block.size(); });
  EXPECT_EQ(counts.rays, settings.pattern.raysPerStation());
  EXPECT_EQ(counts.rays, counts.returns + counts.misses + counts.dropped);
  EXPECT_EQ(delivered, counts.returns);
  EXPECT_GT(counts.misses, counts.rays / 10);
  EXPECT_NEAR(static_cast<double>(counts.dropped) / static_cast<double>(counts.returns + counts.dropped), 0.25, 0.01);
}

TEST(Scanner, MaximumRangeIsRespected) {
  const Scene scene = facadeScene();
  ScannerSettings settings = settingsWith(0.0, 0.5);
  settings.max_range_m = 12.0;
  for (const ScanPoint& p : collect(scene, settings)) {
    ASSERT_LE((p.position - scene.stations[0]).norm(), 12.0 + 1e-9);
  }
}

TEST(Scanner, FurnitureCastsScanShadows) {
  // Seen from the station at (3.3, 2.6), the 2 m cabinet at x 0.5..1.7, y 3.9..4.45 hides the
  // lower part of the y+ wall behind it; the same band further along the wall is well covered.
  const Scene scene = roomScene();
  const auto points = collect(scene, settingsWith(0.0, 0.3));
  PlaneId back_wall = 0;
  for (const TruthPlane& plane : scene.planes) {
    if (plane.name == "room wall y+") back_wall = plane.id;
  }
  int behind_cabinet = 0, open_wall = 0;
  for (const ScanPoint& p : points) {
    if (p.plane != back_wall || p.position.z() < 0.3 || p.position.z() > 1.5) continue;
    if (p.position.x() > 0.4 && p.position.x() < 1.2) ++behind_cabinet;
    if (p.position.x() > 5.2 && p.position.x() < 6.0) ++open_wall;
  }
  EXPECT_EQ(behind_cabinet, 0);
  EXPECT_GT(open_wall, 1000);
}

TEST(Scanner, IntensityFallsWithIncidenceAngle) {
  // A lone floor seen from 1.5 m: next to the scanner (the pattern stops 60 degrees below the
  // horizon) the beam meets it steeply, 10 m away at a graze.
  SceneBuilder b("floor");
  const MaterialId grey = b.material("grey", {128, 128, 128}, 0.5);
  b.quad(b.plane(kZ, 0, +1, "floor"), {{{-30, 30}, {-30, 30}, {0, 0}}}, grey);
  b.station({0, 0, 1.5});
  const Scene scene = std::move(b).build();
  double near_sum = 0, far_sum = 0;
  int near_count = 0, far_count = 0;
  for (const ScanPoint& p : collect(scene, settingsWith(0.0, 0.5))) {
    const double distance = p.position.head<2>().norm();
    EXPECT_GE(p.rgb[0], 124);  // the surface colour with a little jitter
    EXPECT_LE(p.rgb[0], 132);
    if (distance < 1.2) near_sum += p.intensity, ++near_count;
    if (distance > 10.0) far_sum += p.intensity, ++far_count;
  }
  ASSERT_GT(near_count, 0);
  ASSERT_GT(far_count, 0);
  EXPECT_GT(near_sum / near_count, 2.5 * far_sum / far_count);
}

TEST(Scanner, PatternForTargetHitsTheTargetWithinOnePercent) {
  for (const std::string& name : sceneNames()) {
    const Scene scene = makeScene(name);
    const std::vector<Eigen::Vector3d> stations(
        scene.stations.begin(), scene.stations.begin() + static_cast<std::ptrdiff_t>(scene.default_station_count));
    for (std::uint64_t target : {20'000ull, 300'000ull, 1'000'000ull}) {
      ScannerSettings settings = settingsWith(0.002, 1.0);
      settings.dropout = name == "office" ? 0.05 : 0.0;
      settings.pattern = patternForTarget(scene, stations, settings, target);
      std::uint64_t count = 0;
      scan(scene, stations, settings, [&](std::span<const ScanPoint> block) { count += block.size(); });
      EXPECT_NEAR(static_cast<double>(count), static_cast<double>(target), 0.01 * static_cast<double>(target))
          << name << " target " << target;
    }
  }
}

}  // namespace
}  // namespace plumb::reco::sim
