// The data's spacing at a click (reco/data_at_click.h), on clouds whose spacing is known.
#include "reco/data_at_click.h"

#include <gtest/gtest.h>

#include <cmath>

#include "engine/lod/node_cache.h"
#include "engine/lod/octree_builder.h"
#include "tests/support/generated_cloud.h"
#include "tests/support/temp_directory.h"

namespace plumb::reco {
namespace {

const Eigen::Vector3d kUtm(512000.0, 5403000.0, 250.0);

// Two square patches at UTM coordinates in the plane z = 250, 40,000 random points each: a
// sparse one 1 m wide (a point per 5 mm) at x 0..1 and a dense one 0.2 m wide (a point per 1 mm)
// at x 2..2.2. Leaves of at most 5,000 points: the octree's deepest level is far finer than both.
std::shared_ptr<const lod::Octree> buildTwoDensities(const test::TempDirectory& dir) {
  lod::BuildOptions options;
  options.sources = {test::generatedSource(80'000, [](std::uint64_t i) {
    const bool dense = i % 2 == 1;
    const double width = dense ? 0.2 : 1.0;
    const Eigen::Vector3d p = kUtm + Eigen::Vector3d((dense ? 2.0 : 0.0) + width * test::unitHash(i, 1),
                                                     width * test::unitHash(i, 2), 0.0);
    return test::withId(p.x(), p.y(), p.z(), i);
  })};
  options.output = dir.file("two-densities.plumb");
  options.leaf_max_points = 5000;
  lod::buildOctree(options);
  return lod::Octree::open(options.output);
}

TEST(DataAtClick, MeasuresTheSpacingOfThePointsWhereTheUserClicks) {
  test::TempDirectory dir;
  const auto octree = buildTwoDensities(dir);
  lod::NodeCache cache(octree, std::size_t{64} << 20);
  // Random points: the k-th neighbour's distance spreads by about 1 / sqrt(k), 12 %.
  const DataAtClick sparse = dataAtClick(cache, kUtm + Eigen::Vector3d(0.5, 0.5, 0.0));
  EXPECT_NEAR(sparse.spacing_m, 0.005, 0.001);
  const DataAtClick dense = dataAtClick(cache, kUtm + Eigen::Vector3d(2.1, 0.1, 0.0));
  EXPECT_NEAR(dense.spacing_m, 0.001, 0.0002);
  // The deepest level's density, whatever the click: what --detail full asks for.
  EXPECT_DOUBLE_EQ(sparse.full_density, std::pow(octree->spacing(octree->header().depth), -3.0));
  EXPECT_GT(sparse.full_density, std::pow(0.001, -3.0));
}

TEST(DataAtClick, MeasuresAroundTheNearestPointWhereTheClickIsOffTheSurface) {
  test::TempDirectory dir;
  const auto octree = buildTwoDensities(dir);
  lod::NodeCache cache(octree, std::size_t{64} << 20);
  // 10 cm above the sparse patch (a click inside a room's corner): the points around the one
  // the user sees there, not those around a point in the air.
  const double on = dataAtClick(cache, kUtm + Eigen::Vector3d(0.5, 0.5, 0.0)).spacing_m;
  const double above = dataAtClick(cache, kUtm + Eigen::Vector3d(0.5, 0.5, 0.1)).spacing_m;
  EXPECT_NEAR(above, on, 0.15 * on);
}

TEST(DataAtClick, KnowsNothingFarFromThePoints) {
  test::TempDirectory dir;
  const auto octree = buildTwoDensities(dir);
  lod::NodeCache cache(octree, std::size_t{64} << 20);
  EXPECT_EQ(dataAtClick(cache, kUtm + Eigen::Vector3d(0.5, 0.5, 5.0)).spacing_m, 0.0);
}

}  // namespace
}  // namespace plumb::reco
