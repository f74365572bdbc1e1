// Seed planes (paper section 3.4) on hand-made configurations and at a simulated room corner.

#include "reco/seed_planes.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>

#include "engine/core/random.h"
#include "reco/sim/scanner.h"
#include "reco/sim/scenes.h"

namespace plumb::reco {
namespace {

double angleDeg(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::atan2(a.cross(b).norm(), std::abs(a.dot(b))) * 180.0 / M_PI;
}

//        z
//        |  wall x = 0 (points with y, z in [0, 1])
//        |
//        +--------- y
//       /  floor z = 0 (points with x, y in [0, 1])
//      x
// Two planes at 90 degrees, the floor with twice the points: both found, floor first.
TEST(SeedPlanes, TwoPlanesAtRightAngles) {
  Random random(5);
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i < 2000; ++i) points.emplace_back(random.uniform(), random.uniform(), 0.001 * random.gaussian());
  for (int i = 0; i < 1000; ++i) points.emplace_back(0.001 * random.gaussian(), random.uniform(), random.uniform());
  SeedOptions options;
  options.threshold = 0.005;
  const auto planes = findSeedPlanes(points, options);
  ASSERT_EQ(planes.size(), 2u);
  EXPECT_LT(angleDeg(planes[0].plane.normal, Eigen::Vector3d::UnitZ()), 0.5);
  EXPECT_LT(angleDeg(planes[1].plane.normal, Eigen::Vector3d::UnitX()), 0.5);
  EXPECT_GT(planes[0].inliers.size(), planes[1].inliers.size());
  // No point supports two planes.
  std::vector<std::uint32_t> both;
  std::set_intersection(planes[0].inliers.begin(), planes[0].inliers.end(), planes[1].inliers.begin(),
                        planes[1].inliers.end(), std::back_inserter(both));
  EXPECT_TRUE(both.empty());
}

// A plane z = 0 of 3,000 points and a small stray patch y = 0.5 of 200 beside it, 1 mm noise.
std::vector<Eigen::Vector3d> planeAndStrayPatch() {
  Random random(6);
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i < 3000; ++i) points.emplace_back(random.uniform(), random.uniform(), 0.001 * random.gaussian());
  for (int i = 0; i < 200; ++i) {
    points.emplace_back(0.5 + 0.1 * random.uniform(), 0.5 + 0.001 * random.gaussian(), 0.2 + 0.1 * random.uniform());
  }
  return points;
}

SeedOptions strayPatchOptions() {
  SeedOptions options;
  options.threshold = 0.005;
  options.min_inlier_fraction = 0.02;
  return options;
}

// Otsu drops the patch, switching it off keeps it.
TEST(SeedPlanes, OtsuDropsAnUnstablePlane) {
  const std::vector<Eigen::Vector3d> points = planeAndStrayPatch();
  SeedOptions options = strayPatchOptions();
  EXPECT_EQ(findSeedPlanes(points, options).size(), 1u);
  options.drop_unstable = false;
  EXPECT_EQ(findSeedPlanes(points, options).size(), 2u);
}

// The same patch, picked by the user: it is the surface asked for, and stays.
TEST(SeedPlanes, ThePickedPlaneIsNeverDroppedAsUnstable) {
  const std::vector<Eigen::Vector3d> points = planeAndStrayPatch();
  SeedOptions options = strayPatchOptions();
  options.picked = Eigen::Vector3d(0.55, 0.5, 0.25);
  const auto planes = findSeedPlanes(points, options);
  ASSERT_EQ(planes.size(), 2u);
  EXPECT_LT(planes[1].plane.distance(*options.picked), 0.005);
  options.picked = Eigen::Vector3d(0.3, 0.3, 0.0);  // on the big plane: the patch goes
  EXPECT_EQ(findSeedPlanes(points, options).size(), 1u);
}

//        z
//        |   wall x = 0 (y, z in [0, 1]); door leaf x = -0.12 (y, z in [0.5, 1]) behind it
//        |   wall y = 0 (x in [0, 1], z in [0, 1])
//        +--------- y
//       /  floor z = 0 (x, y in [0, 1]), the least supported
//      x
// The door leaf has more points than the floor. It is parallel to the wall, so it does not take
// the floor's slot: all four are found, and max_parallel = 0 leaves the leaf out.
TEST(SeedPlanes, AParallelPlaneDoesNotTakeTheSlotOfACornersThirdPlane) {
  Random random(7);
  std::vector<Eigen::Vector3d> points;
  const auto noise = [&] { return 0.002 * random.gaussian(); };
  for (int i = 0; i < 3000; ++i) points.emplace_back(noise(), random.uniform(), random.uniform());
  for (int i = 0; i < 2000; ++i) points.emplace_back(random.uniform(), noise(), random.uniform());
  for (int i = 0; i < 1200; ++i) {
    points.emplace_back(-0.12 + noise(), 0.5 + 0.5 * random.uniform(), 0.5 + 0.5 * random.uniform());
  }
  for (int i = 0; i < 1000; ++i) points.emplace_back(random.uniform(), random.uniform(), noise());
  SeedOptions options;
  options.threshold = 0.008;
  options.drop_unstable = false;
  const auto planes = findSeedPlanes(points, options);
  ASSERT_EQ(planes.size(), 4u);
  EXPECT_LT(angleDeg(planes[3].plane.normal, Eigen::Vector3d::UnitZ()), 1.0) << "the floor, least supported";
  EXPECT_NEAR(std::abs(planes[2].plane.centroid.x()), 0.12, 0.01) << "the door leaf";
  options.max_parallel = 0;
  const auto corner = findSeedPlanes(points, options);
  ASSERT_EQ(corner.size(), 3u);
  EXPECT_LT(angleDeg(corner[2].plane.normal, Eigen::Vector3d::UnitZ()), 1.0);
}

// The points within 0.6 m of a simulated room corner (2 mm noise): the three walls meeting there.
TEST(SeedPlanes, ThreePlanesAtASimulatedRoomCorner) {
  const sim::Scene room = sim::roomScene();
  sim::ScannerSettings settings;
  settings.noise_m = 0.002;
  settings.pattern = sim::ScanPattern::fromStep(0.25);
  const Eigen::Vector3d corner = room.corners[7].position;  // (7, 5, 2.5): x+, y+ walls and ceiling
  std::vector<Eigen::Vector3d> points;
  sim::scan(room, {room.stations[0]}, settings, [&](std::span<const sim::ScanPoint> block) {
    for (const auto& p : block) {
      if ((p.position - corner).norm() < 0.6) points.push_back(p.position);
    }
  });
  ASSERT_GT(points.size(), 1000u);
  SeedOptions options;
  options.threshold = 0.01;
  const auto planes = findSeedPlanes(points, options);
  for (const auto& plane : planes) {
    std::printf("seed plane: %zu inliers, normal %.3f %.3f %.3f\n", plane.inliers.size(), plane.plane.normal.x(),
                plane.plane.normal.y(), plane.plane.normal.z());
  }
  ASSERT_EQ(planes.size(), 3u);
  // Each seed plane is one of the corner's three true planes (within half a degree), and each
  // true plane is found once.
  std::vector<sim::PlaneId> matched;
  for (const auto& plane : planes) {
    for (sim::PlaneId id : room.corners[7].planes) {
      if (angleDeg(plane.plane.normal, room.planes[id].normal) < 0.5) matched.push_back(id);
    }
  }
  std::sort(matched.begin(), matched.end());
  std::vector<sim::PlaneId> expected(room.corners[7].planes.begin(), room.corners[7].planes.end());
  std::sort(expected.begin(), expected.end());
  EXPECT_EQ(matched, expected);
}

}  // namespace
}  // namespace plumb::reco
