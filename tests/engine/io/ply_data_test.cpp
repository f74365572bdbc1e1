// The PLY reader on the real scans of ../shared/data/real (skipped when absent).

#include <gtest/gtest.h>

#include <cmath>

#include "engine/io/point_reader.h"
#include "tests/support/shared_data.h"

namespace plumb::io {
namespace {

struct Summary {
  std::uint64_t points = 0;
  double sum_x = 0, sum_y = 0, sum_z = 0;
  std::uint64_t intensity_sum = 0;
  std::uint64_t colour_sum = 0;
  std::size_t normals = 0;
};

Summary summarise(PointReader& reader) {
  Summary s;
  PointBatch batch;
  while (reader.read(batch, 50'000)) {
    for (const PointRecord& p : batch.points) {
      ++s.points;
      s.sum_x += p.x;
      s.sum_y += p.y;
      s.sum_z += p.z;
      s.intensity_sum += p.intensity;
      s.colour_sum += std::uint64_t{p.rgb[0]} + p.rgb[1] + p.rgb[2];
    }
    s.normals += batch.normals.size();
  }
  return s;
}

TEST(PlyRealData, RoomScanHasItsKnownCount) {
  PLUMB_REQUIRE_SHARED_DATA(path, "pcl_room_scan1.ply");
  const auto reader = openPointCloud(path);
  const Summary s = summarise(*reader);
  EXPECT_EQ(s.points, 112'586u);
  EXPECT_EQ(reader->counts().non_finite, 0u);
  EXPECT_TRUE(std::isfinite(s.sum_x + s.sum_y + s.sum_z));
}

TEST(PlyRealData, FacadesKeepFloatIntensityAndListTheLabels) {
  PLUMB_REQUIRE_SHARED_DATA(path, "nuist_commercial_street_facades.ply");
  const auto reader = openPointCloud(path);
  EXPECT_TRUE(reader->info().attributes.intensity);
  EXPECT_EQ(reader->info().ignored_fields, (std::vector<std::string>{"label", "building", "instance"}));
  const Summary s = summarise(*reader);
  EXPECT_EQ(s.points, 199'235u);
  EXPECT_GT(s.intensity_sum, 0u);
}

TEST(PlyRealData, City3dKeepsNormalsAndColour) {
  PLUMB_REQUIRE_SHARED_DATA(path, "city3d_001.ply");
  const auto reader = openPointCloud(path);
  EXPECT_TRUE(reader->info().attributes.normals);
  EXPECT_TRUE(reader->info().attributes.colour);
  const Summary s = summarise(*reader);
  EXPECT_EQ(s.points, 57'379u);
  EXPECT_EQ(s.normals, 57'379u);
  EXPECT_GT(s.colour_sum, 0u);
}

}  // namespace
}  // namespace plumb::io
