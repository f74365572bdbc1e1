// Tests of the PCD reader on the real scans in ../shared/data/real (all binary_compressed):
//
//   1. The PCL room scans: their known point counts, no invalid points; scan 1 against the same
//      points in pcl_room_scan1.ply (read here by hand), compared as sorted lists.
//   2. The organized Kinect frame: 254,456 valid of 307,200 pixels, with colour.
//   3. The ISPRS airborne scan in UTM coordinates: count, extent, and no error added to the
//      file's float32 values.
// Each test skips when its file is absent.

#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <fstream>

#include "engine/io/point_reader.h"
#include "tests/support/shared_data.h"

namespace plumb::io {
namespace {

struct Cloud {
  std::vector<PointRecord> points;
  CloudInfo info;
  ReadCounts counts;
};

Cloud readAll(const std::string& path) {
  auto reader = openPcd(path);
  Cloud cloud;
  PointBatch batch;
  while (reader->read(batch, 50000)) cloud.points.insert(cloud.points.end(), batch.points.begin(), batch.points.end());
  cloud.info = reader->info();
  cloud.counts = reader->counts();
  return cloud;
}

void expectCounts(const Cloud& cloud, std::uint64_t declared, std::uint64_t valid) {
  EXPECT_EQ(cloud.info.format, "PCD 0.7 binary_compressed");
  EXPECT_EQ(cloud.info.declared_points, declared);
  EXPECT_EQ(cloud.counts.delivered, valid);
  EXPECT_EQ(cloud.counts.non_finite, declared - valid);
  EXPECT_EQ(cloud.points.size(), valid);
}

// The float x y z of a binary little-endian PLY whose vertex has only float properties
// (pcl_room_scan1.ply), parsed by hand so that the check does not trust the PLY reader.
std::vector<std::array<float, 3>> readPlyFloats(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::string line;
  std::size_t count = 0;
  std::vector<std::string> properties;
  while (std::getline(in, line) && line != "end_header") {
    if (line.rfind("element vertex ", 0) == 0) count = std::stoul(line.substr(15));
    if (line.rfind("property float ", 0) == 0) properties.push_back(line.substr(15));
  }
  EXPECT_EQ(properties, (std::vector<std::string>{"x", "y", "z"})) << "unexpected layout in " << path;
  std::vector<std::array<float, 3>> points(count);
  in.read(reinterpret_cast<char*>(points.data()), static_cast<std::streamsize>(count * sizeof(points[0])));
  EXPECT_TRUE(in.good()) << path << " is truncated";
  return points;
}

TEST(PcdData, RoomScan1MatchesItsPly) {
  PLUMB_REQUIRE_SHARED_DATA(path, "pcl_room_scan1.pcd");
  const Cloud cloud = readAll(path);
  expectCounts(cloud, 112586, 112586);
  EXPECT_FALSE(cloud.info.attributes.colour);
  EXPECT_TRUE(cloud.info.ignored_fields.empty());

  PLUMB_REQUIRE_SHARED_DATA(points_path, "pcl_room_scan1.ply");
  auto ply = readPlyFloats(points_path);
  std::vector<std::array<float, 3>> pcd;
  for (const auto& p : cloud.points) {
    pcd.push_back({static_cast<float>(p.x), static_cast<float>(p.y), static_cast<float>(p.z)});
  }
  std::sort(ply.begin(), ply.end());
  std::sort(pcd.begin(), pcd.end());
  EXPECT_TRUE(ply == pcd) << "the PCD and PLY copies of room scan 1 hold different points";
}

TEST(PcdData, RoomScan2) {
  PLUMB_REQUIRE_SHARED_DATA(path, "pcl_room_scan2.pcd");
  expectCounts(readAll(path), 112624, 112624);
}

TEST(PcdData, Office1KinectOrganizedWithColour) {
  PLUMB_REQUIRE_SHARED_DATA(path, "pcl_office1_kinect.pcd");
  const Cloud cloud = readAll(path);
  expectCounts(cloud, 307200, 254456);
  EXPECT_EQ(cloud.counts.non_finite, 52744u);
  ASSERT_TRUE(cloud.info.attributes.colour);
  // A real colour image: not all one colour, and the extent of the documented scene.
  std::size_t coloured = 0;
  double max_depth = 0;
  for (const auto& point : cloud.points) {
    if (point.rgb != cloud.points.front().rgb) ++coloured;
    max_depth = std::max(max_depth, point.z);
  }
  EXPECT_GT(coloured, cloud.points.size() / 2);
  EXPECT_GT(max_depth, 1.0);
  EXPECT_LT(max_depth, 10.0);
}

TEST(PcdData, IsprsUtmCoordinatesKeptExactly) {
  PLUMB_REQUIRE_SHARED_DATA(path, "isprs_CSite1_red1-utm.pcd");
  const Cloud cloud = readAll(path);
  expectCounts(cloud, 522674, 522674);
  std::size_t outside = 0;
  std::size_t altered = 0;
  for (const auto& p : cloud.points) {
    if (p.x < 511000 || p.x > 514000 || p.y < 5402000 || p.y > 5405000) ++outside;
    // The file stores float32: a value read back must be exactly a float32 (no error added).
    for (const double v : {p.x, p.y, p.z}) {
      if (static_cast<double>(static_cast<float>(v)) != v) ++altered;
    }
  }
  EXPECT_EQ(outside, 0u);
  EXPECT_EQ(altered, 0u);
}

}  // namespace
}  // namespace plumb::io
