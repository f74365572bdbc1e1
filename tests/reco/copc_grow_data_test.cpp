// The grower on COPC files opened in place (engine/lod's COPC backend), on the reference files of
// ../shared/data/formats/copc (skipped when absent): the same API as on a Plumb octree, and a
// click loads only the nodes around it.

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <cmath>
#include <string>

#include "engine/io/copc_file.h"
#include "engine/lod/node_cache.h"
#include "engine/lod/octree.h"
#include "reco/data_at_click.h"
#include "reco/region_grower.h"
#include "tests/support/copc_mosaic.h"
#include "tests/support/shared_data.h"
#include "tests/support/temp_directory.h"

namespace plumb::reco {
namespace {

// A point of the ground of lone-star.copc.laz, a 41 m tile of airborne lidar (bare ground
// around a stand of trees).
const Eigen::Vector3d kGroundPoint(515388.976, 4918368.237, 2325.016);

// A click as plumb grow makes it, seen from 3 m.
GrowSnapshot growAt(lod::NodeCache& cache, const Eigen::Vector3d& seed) {
  return growRegions(cache, parametersForView(viewFromDistance(seed, 3.0), {}, dataAtClick(cache, seed)));
}

void expectGroundAt(const GrowSnapshot& result, const Eigen::Vector3d& seed) {
  ASSERT_TRUE(result.converged);
  ASSERT_FALSE(result.segments.empty());
  const SegmentSnapshot* nearest = &result.segments.front();
  for (const SegmentSnapshot& segment : result.segments) {
    if (segment.plane.distance(seed) < nearest->plane.distance(seed)) nearest = &segment;
  }
  EXPECT_LT(nearest->plane.distance(seed), 0.05);
  EXPECT_GT(std::abs(nearest->plane.normal.z()), 0.9) << "ground: a plane near the horizontal";
  EXPECT_GT(nearest->points, 100u);
}

TEST(GrowCopc, GrowsOnTheLargestReferenceFileInPlace) {
  PLUMB_REQUIRE_FORMAT_FILE(path, "copc/lone-star.copc.laz");
  lod::NodeCache cache(lod::Octree::open(path), 256 << 20);
  expectGroundAt(growAt(cache, kGroundPoint), kGroundPoint);
  EXPECT_LT(cache.stats().misses, cache.octree().nodes().size());
}

// 4 x 4 copies of lone-star (245 nodes, 8.3 M points): a click on one copy reads the nodes
// around it, a few per cent of the file.
TEST(GrowCopc, AClickLoadsOnlyTheNodesAroundIt) {
  PLUMB_REQUIRE_FORMAT_FILE(tile, "copc/lone-star.copc.laz");
  test::TempDirectory dir;
  const std::string path = dir.file("mosaic.copc.laz");
  test::writeCopcMosaic(tile, 2, path);
  lod::NodeCache cache(lod::Octree::open(path), 256 << 20);
  const lod::Octree& octree = cache.octree();

  // The same ground point in the copy one tile along x and y.
  const double tile_size = 2.0 * io::CopcFile(tile).info().halfsize;
  const Eigen::Vector3d seed = kGroundPoint + Eigen::Vector3d(tile_size, tile_size, 0.0);
  expectGroundAt(growAt(cache, seed), seed);

  std::uint64_t file_bytes = 0;
  for (const lod::NodeInfo& node : octree.nodes()) file_bytes += node.bytes;
  const lod::NodeCacheStats stats = cache.stats();
  RecordProperty("nodes_loaded", std::to_string(stats.misses) + " of " + std::to_string(octree.nodes().size()));
  EXPECT_LE(stats.misses * 10, octree.nodes().size()) << "a click reads at most a tenth of the nodes";
  EXPECT_LE(stats.bytes_read * 10, file_bytes) << "and at most a tenth of the chunks' bytes";
}

}  // namespace
}  // namespace plumb::reco
