// The flat neighbour-grid tables of the region grower against std containers.

#include "reco/grid_index.h"

#include <gtest/gtest.h>

#include <map>
#include <tuple>
#include <vector>

#include "engine/core/random.h"
#include "reco/grid_map.h"

namespace plumb::reco {
namespace {

auto tupleOf(const GridKey& k) {
  return std::make_tuple(k.x, k.y, k.z);
}

// Points around a UTM-like origin and on both sides of it (negative grid keys): every grid cell's
// bucket holds exactly its points, ascending; cells with no point give nothing.
TEST(GridIndex, BucketsEveryPointOnceInAscendingOrder) {
  Random random(3);
  const Eigen::Vector3d origin(512000.0, 5403000.0, 250.0);
  const PointGrid grid(origin, 0.05);
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i < 5000; ++i) {
    points.push_back(origin +
                     Eigen::Vector3d(random.uniform() - 0.5, random.uniform() - 0.5, 0.01 * random.gaussian()));
  }
  std::map<std::tuple<std::int64_t, std::int64_t, std::int64_t>, std::vector<std::uint32_t>> expected;
  for (std::uint32_t i = 0; i < points.size(); ++i) expected[tupleOf(grid.keyOf(points[i]))].push_back(i);
  const GridIndex index(grid, points);
  std::size_t found = 0;
  for (const auto& [key, indices] : expected) {
    const auto bucket = index.at({std::get<0>(key), std::get<1>(key), std::get<2>(key)});
    EXPECT_EQ(std::vector<std::uint32_t>(bucket.begin(), bucket.end()), indices);
    found += bucket.size();
  }
  EXPECT_EQ(found, points.size());
  EXPECT_TRUE(index.at({1000, 1000, 1000}).empty());
  EXPECT_TRUE(GridIndex().at({0, 0, 0}).empty());
}

// Insertions past several rehashes keep every value under its key; clear empties the map.
TEST(GridMap, KeepsEveryValueAcrossRehashes) {
  GridMap<int> map;
  EXPECT_EQ(map.find({0, 0, 0}), nullptr);
  for (std::int64_t i = 0; i < 3000; ++i) map[{i % 17 - 8, i / 17 - 80, -i}] = static_cast<int>(i);
  for (std::int64_t i = 0; i < 3000; ++i) {
    const int* value = map.find({i % 17 - 8, i / 17 - 80, -i});
    ASSERT_NE(value, nullptr) << i;
    EXPECT_EQ(*value, i);
  }
  EXPECT_EQ(map.find({9, 9, 9}), nullptr);
  map[{1, 2, 3}] += 5;
  EXPECT_EQ(*map.find({1, 2, 3}), 5);
  map.clear();
  EXPECT_EQ(map.find({1, 2, 3}), nullptr);
}

}  // namespace
}  // namespace plumb::reco
