// Octrees of the real scans in ../shared/data/real (skipped when absent): every point the
// reader delivers is in the octree once, with its position and attributes.

#include <gtest/gtest.h>

#include <cmath>

#include "engine/lod/octree.h"
#include "engine/lod/octree_builder.h"
#include "tests/support/shared_data.h"
#include "tests/support/temp_directory.h"

namespace plumb::lod {
namespace {

// Order-independent sums over a cloud: count, coordinates relative to a reference, attributes.
struct Checksum {
  std::uint64_t count = 0;
  double x = 0, y = 0, z = 0;
  std::uint64_t attributes = 0;

  void add(double px, double py, double pz, const std::array<std::uint16_t, 3>& rgb, std::uint16_t intensity,
           const std::array<double, 3>& reference) {
    ++count;
    x += px - reference[0];
    y += py - reference[1];
    z += pz - reference[2];
    attributes += std::uint64_t{rgb[0]} + 3u * rgb[1] + 7u * rgb[2] + 11u * intensity;
  }
};

void expectRoundTrip(const std::string& path) {
  test::TempDirectory dir;
  BuildOptions options;
  options.sources = fileSources({path});
  options.output = dir.file("scan.plumb");
  options.memory_mb = 64;  // several chunks even for these small scans
  options.leaf_max_points = 5000;
  const BuildReport report = buildOctree(options);
  const auto octree = Octree::open(options.output);
  const std::array<double, 3> reference = octree->cube().origin;

  Checksum input;
  const auto reader = io::openPointCloud(path);
  io::PointBatch batch;
  while (reader->read(batch, 100'000)) {
    for (const auto& p : batch.points) input.add(p.x, p.y, p.z, p.rgb, p.intensity, reference);
  }
  Checksum stored;
  for (const NodeInfo& node : octree->nodes()) {
    const NodePoints points = octree->load(node);
    for (std::size_t i = 0; i < points.size(); ++i) {
      const auto p = points.position(i);
      stored.add(p[0], p[1], p[2], points.points[i].rgb, points.points[i].intensity, reference);
    }
  }
  EXPECT_EQ(stored.count, input.count);
  EXPECT_EQ(report.points, input.count);
  EXPECT_EQ(octree->header().skipped_non_finite, reader->counts().non_finite);
  EXPECT_EQ(stored.attributes, input.attributes);
  // Float offsets within a cell: sub-micrometre per point on these extents.
  const double tolerance = 1e-5 * static_cast<double>(input.count);
  EXPECT_NEAR(stored.x, input.x, tolerance);
  EXPECT_NEAR(stored.y, input.y, tolerance);
  EXPECT_NEAR(stored.z, input.z, tolerance);
}

TEST(OctreeRealData, RoomScanPcd) {
  PLUMB_REQUIRE_SHARED_DATA(path, "pcl_room_scan1.pcd");
  expectRoundTrip(path);
}

TEST(OctreeRealData, OrganisedKinectFrameWithColour) {
  PLUMB_REQUIRE_SHARED_DATA(path, "pcl_office1_kinect.pcd");
  expectRoundTrip(path);
}

TEST(OctreeRealData, AirborneUtmScan) {
  PLUMB_REQUIRE_SHARED_DATA(path, "isprs_CSite1_red1-utm.pcd");
  expectRoundTrip(path);
}

TEST(OctreeRealData, FacadesWithIntensity) {
  PLUMB_REQUIRE_SHARED_DATA(path, "nuist_commercial_street_facades.ply");
  expectRoundTrip(path);
}

}  // namespace
}  // namespace plumb::lod
