// The region growing loop (paper section 3.5) on small octrees with a known truth.

#include "reco/region_grower.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "engine/lod/lod_query.h"
#include "engine/lod/octree_builder.h"
#include "tests/support/generated_cloud.h"
#include "tests/support/temp_directory.h"

namespace plumb::reco {
namespace {

double angleDeg(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::atan2(a.cross(b).norm(), std::abs(a.dot(b))) * 180.0 / M_PI;
}

// A cloud of planar patches at UTM coordinates with 1 mm noise; the patch of each point is
// known from its index (test::unitHash decides).
struct Patch {
  Eigen::Vector3d origin, u, v;  // the patch is origin + a u + b v, a and b in [0, 1]
};

std::shared_ptr<const lod::Octree> buildPatches(const test::TempDirectory& dir, const std::vector<Patch>& patches,
                                                std::uint64_t count) {
  lod::BuildOptions options;
  options.sources = {test::generatedSource(count, [patches](std::uint64_t i) {
    const Patch& patch = patches[i % patches.size()];
    const Eigen::Vector3d normal = patch.u.cross(patch.v).normalized();
    const double noise =
        0.001 * std::sqrt(-2.0 * std::log(1.0 - test::unitHash(i, 3))) * std::cos(2.0 * M_PI * test::unitHash(i, 4));
    const Eigen::Vector3d p =
        patch.origin + test::unitHash(i, 1) * patch.u + test::unitHash(i, 2) * patch.v + noise * normal;
    return test::withId(p.x(), p.y(), p.z(), i % patches.size());
  })};
  options.output = dir.file("patches.plumb");
  options.leaf_max_points = 5000;
  lod::buildOctree(options);
  return lod::Octree::open(options.output);
}

// How many points of patch `id` the octree holds at `level` (and above): what a grow at that
// level can find.
std::uint64_t pointsOfPatchAtLevel(lod::NodeCache& cache, std::uint32_t level, std::uint16_t id) {
  std::uint64_t count = 0;
  for (const lod::NodeInfo& node : cache.octree().nodes()) {
    if (node.key.level > level) continue;
    const auto points = cache.get(node.key);
    for (const auto& p : points->points) count += p.rgb[0] == id ? 1u : 0u;
  }
  return count;
}

const Eigen::Vector3d kUtm(512000.0, 5403000.0, 250.0);

//   z
//   |  wall: x = 0, y in [0, 4], z in [0, 2.5]
//   |
//   +---------- y
//  /   floor: z = 0, x in [0, 4], y in [0, 4]
// x    seed near the edge where they meet
TEST(RegionGrower, TwoPlanesAtRightAnglesGrowApart) {
  test::TempDirectory dir;
  const std::vector<Patch> patches{{kUtm, {4, 0, 0}, {0, 4, 0}}, {kUtm, {0, 4, 0}, {0, 0, 2.5}}};
  const auto octree = buildPatches(dir, patches, 120'000);
  lod::NodeCache cache(octree, 256 << 20);

  const GrowParameters parameters =
      parametersForDensity(kUtm + Eigen::Vector3d(0.3, 2.0, 0.3), 1.0 / std::pow(0.03, 3), 0.5);
  std::vector<GrowSnapshot> snapshots;
  const GrowSnapshot result =
      growRegions(cache, parameters, {}, [&](const GrowSnapshot& s) { snapshots.push_back(s); });

  ASSERT_TRUE(result.converged);
  ASSERT_EQ(result.segments.size(), 2u);
  const std::uint64_t floor_points = pointsOfPatchAtLevel(cache, result.level, 0);
  const std::uint64_t wall_points = pointsOfPatchAtLevel(cache, result.level, 1);
  int floors = 0, walls = 0;
  for (const SegmentSnapshot& segment : result.segments) {
    ASSERT_TRUE(segment.plane.valid);
    if (angleDeg(segment.plane.normal, Eigen::Vector3d::UnitZ()) < 0.2) {
      ++floors;
      EXPECT_NEAR(static_cast<double>(segment.points), static_cast<double>(floor_points),
                  0.03 * static_cast<double>(floor_points));
      EXPECT_NEAR(segment.plane.signedDistance(kUtm), 0.0, 0.0005);
    } else if (angleDeg(segment.plane.normal, Eigen::Vector3d::UnitX()) < 0.2) {
      ++walls;
      EXPECT_NEAR(static_cast<double>(segment.points), static_cast<double>(wall_points),
                  0.03 * static_cast<double>(wall_points));
    }
  }
  EXPECT_EQ(floors, 1);
  EXPECT_EQ(walls, 1);

  // Snapshots come in order, each a valid intermediate result.
  ASSERT_GE(snapshots.size(), 2u);
  for (std::size_t i = 1; i < snapshots.size(); ++i) {
    std::uint64_t before = 0, after = 0;
    for (const auto& s : snapshots[i - 1].segments) before += s.points;
    for (const auto& s : snapshots[i].segments) after += s.points;
    EXPECT_LE(before, after);
  }
  EXPECT_GT(result.mean_neighbour_distance, 0.0);
  EXPECT_LE(result.mean_neighbour_distance, parameters.search_radius_m);
}

//   x = 0      x = 0.1
//     |          |      a 10 cm thick wall: two faces, 3 m x 2.5 m each, 2 cm plane threshold
//     |  (wall)  |
// A seed sphere reaching both faces seeds both, and each grows over its own face only; a
// small one on the first face grows that face alone.
TEST(RegionGrower, TheTwoFacesOfAThickWallStayApart) {
  test::TempDirectory dir;
  const std::vector<Patch> patches{{kUtm, {0, 3, 0}, {0, 0, 2.5}},
                                   {kUtm + Eigen::Vector3d(0.1, 0, 0), {0, 3, 0}, {0, 0, 2.5}}};
  const auto octree = buildPatches(dir, patches, 80'000);
  lod::NodeCache cache(octree, 256 << 20);
  const Eigen::Vector3d seed = kUtm + Eigen::Vector3d(0, 1.5, 1.2);

  GrowParameters both = parametersForDensity(seed, 1.0 / std::pow(0.03, 3), 0.4);
  both.plane_threshold_m = 0.02;
  const GrowSnapshot two = growRegions(cache, both);
  ASSERT_EQ(two.segments.size(), 2u);
  std::vector<double> offsets;
  for (const SegmentSnapshot& segment : two.segments) {
    EXPECT_LT(angleDeg(segment.plane.normal, Eigen::Vector3d::UnitX()), 0.2);
    offsets.push_back(std::abs(segment.plane.signedDistance(kUtm)));
    const std::uint64_t face = pointsOfPatchAtLevel(cache, two.level, offsets.back() < 0.05 ? 0 : 1);
    EXPECT_NEAR(static_cast<double>(segment.points), static_cast<double>(face), 0.03 * static_cast<double>(face));
  }
  std::sort(offsets.begin(), offsets.end());
  EXPECT_NEAR(offsets[0], 0.0, 0.0005);
  EXPECT_NEAR(offsets[1], 0.1, 0.0005);

  GrowParameters one = parametersForDensity(seed, 1.0 / std::pow(0.03, 3), 0.06);
  one.plane_threshold_m = 0.02;
  const GrowSnapshot single = growRegions(cache, one);
  ASSERT_EQ(single.segments.size(), 1u);
  EXPECT_NEAR(single.segments[0].plane.signedDistance(kUtm), 0.0, 0.0005);
  const std::uint64_t face = pointsOfPatchAtLevel(cache, single.level, 0);
  EXPECT_NEAR(static_cast<double>(single.segments[0].points), static_cast<double>(face),
              0.03 * static_cast<double>(face));
}

//   +---------------------+
//   |        floor        |   a 4 x 4 m floor with no points in a 0.8 x 0.8 m square: the scan
//   |    +----+           |   shadow of an occluder. Growing from one side reaches all around
//   |    |    |  seed     |   the hole: the segment gets every floor point.
//   |    +----+           |
//   +---------------------+
TEST(RegionGrower, GrowthGoesAroundAScanShadow) {
  test::TempDirectory dir;
  lod::BuildOptions options;
  options.sources = {test::generatedSource(80'000, [](std::uint64_t i) {
    const double x = 4.0 * test::unitHash(i, 1), y = 4.0 * test::unitHash(i, 2);
    const bool in_shadow = x > 1.2 && x < 2.0 && y > 1.2 && y < 2.0;
    const double z = in_shadow ? NAN : 0.0005 * (test::unitHash(i, 3) - 0.5);
    return test::withId(kUtm.x() + x, kUtm.y() + y, kUtm.z() + z, 0);
  })};
  options.output = dir.file("shadow.plumb");
  options.leaf_max_points = 5000;
  lod::buildOctree(options);
  lod::NodeCache cache(lod::Octree::open(options.output), 256 << 20);
  const GrowSnapshot result =
      growRegions(cache, parametersForDensity(kUtm + Eigen::Vector3d(3.0, 1.6, 0.0), 1.0 / std::pow(0.03, 3), 0.3));
  ASSERT_EQ(result.segments.size(), 1u);
  const std::uint64_t floor = pointsOfPatchAtLevel(cache, result.level, 0);
  EXPECT_NEAR(static_cast<double>(result.segments[0].points), static_cast<double>(floor),
              0.02 * static_cast<double>(floor));
}

TEST(RegionGrower, ACancelledGrowStopsAtTheNextCell) {
  test::TempDirectory dir;
  const auto octree = buildPatches(dir, {{kUtm, {4, 0, 0}, {0, 4, 0}}}, 40'000);
  lod::NodeCache cache(octree, 256 << 20);
  std::atomic<bool> cancel{true};
  GrowOptions options;
  options.cancel = &cancel;
  const GrowSnapshot result =
      growRegions(cache, parametersForDensity(kUtm + Eigen::Vector3d(2, 2, 0), 1.0 / std::pow(0.03, 3), 0.5), options);
  EXPECT_TRUE(result.cancelled);
  EXPECT_FALSE(result.converged);
  EXPECT_EQ(result.cells_visited, 0u);
}

TEST(RegionGrower, NoPlaneAtTheSeedIsNoSegment) {
  test::TempDirectory dir;
  const auto octree = buildPatches(dir, {{kUtm, {4, 0, 0}, {0, 4, 0}}}, 40'000);
  lod::NodeCache cache(octree, 256 << 20);
  // Far from every point: the seed sphere is empty.
  const GrowSnapshot result =
      growRegions(cache, parametersForDensity(kUtm + Eigen::Vector3d(2, 2, 3), 1.0 / std::pow(0.03, 3), 0.5));
  EXPECT_TRUE(result.converged);
  EXPECT_TRUE(result.segments.empty());
}

}  // namespace
}  // namespace plumb::reco
