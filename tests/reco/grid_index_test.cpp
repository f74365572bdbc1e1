// The flat neighbour-grid tables of the region grower against std containers.

#include "reco/grid_index.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
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
  // bucket(): the same indices, where they start in order(), each with its position relative to
  // the grid's origin in floats.
  for (const auto& [key, indices] : expected) {
    const GridIndex::Bucket bucket = index.bucket({std::get<0>(key), std::get<1>(key), std::get<2>(key)});
    ASSERT_EQ(std::vector<std::uint32_t>(bucket.indices.begin(), bucket.indices.end()), indices);
    ASSERT_EQ(bucket.x.size(), indices.size());
    ASSERT_EQ(bucket.y.size(), indices.size());
    ASSERT_EQ(bucket.z.size(), indices.size());
    for (std::size_t k = 0; k < indices.size(); ++k) {
      EXPECT_EQ(index.order()[bucket.first + k], indices[k]);
      EXPECT_EQ(Eigen::Vector3f(bucket.x[k], bucket.y[k], bucket.z[k]), (points[indices[k]] - origin).cast<float>());
    }
  }
  EXPECT_TRUE(index.bucket({1000, 1000, 1000}).indices.empty());
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

// The 8 cells nearest a point hold every point within half a step of it, on both sides of the
// origin and at the cells' faces, and are 8 distinct cells with p's own among them.
TEST(PointGrid, TheEightNearestCellsHoldEveryPointWithinHalfAStep) {
  Random random(5);
  const Eigen::Vector3d origin(512000.0, 5403000.0, 250.0);
  const double step = 0.1;
  const PointGrid grid(origin, step);
  std::size_t checked = 0;
  for (int i = 0; i < 2000; ++i) {
    const Eigen::Vector3d p =
        origin + Eigen::Vector3d(random.uniform() - 0.5, random.uniform() - 0.5, random.uniform() - 0.5);
    std::vector<std::tuple<std::int64_t, std::int64_t, std::int64_t>> visited;
    grid.forEachNear(p, [&](const GridKey& key) { visited.push_back(tupleOf(key)); });
    std::sort(visited.begin(), visited.end());
    ASSERT_EQ(std::unique(visited.begin(), visited.end()), visited.end());
    ASSERT_EQ(visited.size(), 8u);
    EXPECT_TRUE(std::binary_search(visited.begin(), visited.end(), tupleOf(grid.keyOf(p))));
    for (int j = 0; j < 20; ++j) {
      // A point at most half a step away, many of them right at that distance.
      Eigen::Vector3d offset(random.gaussian(), random.gaussian(), random.gaussian());
      offset *= (j % 2 == 0 ? 0.5 : 0.5 * random.uniform()) * step / offset.norm();
      const Eigen::Vector3d q = p + offset * (1.0 - 1e-9);
      EXPECT_TRUE(std::binary_search(visited.begin(), visited.end(), tupleOf(grid.keyOf(q))))
          << "point " << i << ", neighbour " << j;
      ++checked;
    }
  }
  EXPECT_EQ(checked, 40000u);
}

// The cells around a point within one step: in forEachAround's order (p's own first), every cell
// forEachAround gives that holds a point within the step, and on average about 20.6 of the 27.
TEST(PointGrid, TheCellsWithinAStepAreThoseAroundThatCanHoldAPointWithinIt) {
  Random random(7);
  const Eigen::Vector3d origin(512000.0, 5403000.0, 250.0);
  const double step = 0.05;
  const PointGrid grid(origin, step);
  std::size_t visited_total = 0;
  constexpr int kPoints = 4000;
  for (int i = 0; i < kPoints; ++i) {
    const Eigen::Vector3d p =
        origin + Eigen::Vector3d(random.uniform() - 0.5, random.uniform() - 0.5, random.uniform() - 0.5);
    std::vector<std::tuple<std::int64_t, std::int64_t, std::int64_t>> around;
    grid.forEachAround(p, [&](const GridKey& key) { around.push_back(tupleOf(key)); });
    std::vector<std::tuple<std::int64_t, std::int64_t, std::int64_t>> within;
    grid.forEachAroundWithin(p, step, [&](const GridKey& key) { within.push_back(tupleOf(key)); });
    ASSERT_FALSE(within.empty());
    EXPECT_EQ(within.front(), tupleOf(grid.keyOf(p)));
    // A subsequence of forEachAround's order.
    auto next = around.begin();
    for (const auto& key : within) {
      next = std::find(next, around.end(), key);
      ASSERT_NE(next, around.end()) << "point " << i;
    }
    visited_total += within.size();
    for (int j = 0; j < 20; ++j) {
      Eigen::Vector3d offset(random.gaussian(), random.gaussian(), random.gaussian());
      offset *= (j % 2 == 0 ? 1.0 : random.uniform()) * step / offset.norm();
      const auto key = tupleOf(grid.keyOf(p + offset * (1.0 - 1e-9)));
      EXPECT_NE(std::find(within.begin(), within.end(), key), within.end()) << "point " << i << ", neighbour " << j;
    }
  }
  const double mean = static_cast<double>(visited_total) / kPoints;
  EXPECT_NEAR(mean, 1.0 + 6.0 + 12.0 * M_PI / 4.0 + 8.0 * M_PI / 6.0, 0.3);
}

}  // namespace
}  // namespace plumb::reco
