// Edges and corners (paper section 4.1) on hand-made segments with a known intersection.

#include "reco/edges_and_corners.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>

#include "engine/core/random.h"
#include "reco/plane_regression.h"

namespace plumb::reco {
namespace {

const Eigen::Vector3d kUtm(512000.0, 5403000.0, 250.0);

// Points on origin + a u + b v (a, b in [0, 1]) with 1 mm noise along the normal.
std::vector<Eigen::Vector3d> patch(const Eigen::Vector3d& origin, const Eigen::Vector3d& u, const Eigen::Vector3d& v,
                                   int count, std::uint64_t seed) {
  Random random(seed);
  const Eigen::Vector3d normal = u.cross(v).normalized();
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i < count; ++i) {
    points.push_back(origin + random.uniform() * u + random.uniform() * v + 0.001 * random.gaussian() * normal);
  }
  return points;
}

Plane fit(const std::vector<Eigen::Vector3d>& points) {
  PlaneRegression regression;
  for (const auto& p : points) regression.add(p);
  return regression.fit();
}

//      z
//      |  wall x = 0 (y 0..4, z 0..2.5)
//      |        wall y = 0 (x 0..3, z 0..2.5)
//      +------ y
//     /  floor z = 0 (x 0..3, y 0..4)
//    x   three edges along the axes from the corner at the UTM origin, and the corner itself
TEST(EdgesAndCorners, ARoomCornerGivesThreeEdgesAndOneCorner) {
  const auto floor = patch(kUtm, {3, 0, 0}, {0, 4, 0}, 20000, 1);
  const auto wall_x = patch(kUtm, {0, 4, 0}, {0, 0, 2.5}, 12000, 2);
  const auto wall_y = patch(kUtm, {3, 0, 0}, {0, 0, 2.5}, 9000, 3);
  const std::vector<SegmentGeometry> segments{{fit(floor), floor}, {fit(wall_x), wall_x}, {fit(wall_y), wall_y}};
  FeatureOptions options;
  options.search_radius = 0.05;  // twice the floor's point spacing, as the grower sets it
  const Features features = findEdgesAndCorners(segments, options);

  ASSERT_EQ(features.corners.size(), 1u);
  EXPECT_LT((features.corners[0].position - kUtm).norm(), 0.0005);
  for (double variance : features.corners[0].support) EXPECT_NEAR(std::sqrt(variance), 0.001, 0.0002);

  ASSERT_EQ(features.edges.size(), 3u);
  for (const Edge& edge : features.edges) {
    // Every edge runs along an axis through the corner, between the 5th and 95th percentile.
    const Eigen::Vector3d axis = edge.direction.cwiseAbs();
    const int along = axis.x() > 0.99 ? 0 : axis.y() > 0.99 ? 1 : 2;
    const double length = along == 0 ? 3.0 : along == 1 ? 4.0 : 2.5;
    for (const Eigen::Vector3d& end : {edge.start, edge.end}) {
      const Eigen::Vector3d offset = end - kUtm;
      for (int a = 0; a < 3; ++a) {
        if (a != along) {
          EXPECT_NEAR(offset[a], 0.0, 0.0005);
        }
      }
    }
    const double low = std::min((edge.start - kUtm)[along], (edge.end - kUtm)[along]);
    const double high = std::max((edge.start - kUtm)[along], (edge.end - kUtm)[along]);
    EXPECT_NEAR(low, 0.05 * length, 0.05 * length);
    EXPECT_NEAR(high, 0.95 * length, 0.05 * length);
    EXPECT_GT(edge.support_points, 100u);
  }
}

// Parallel planes do not meet; planes whose points stay far from their intersection do not
// make an edge there.
TEST(EdgesAndCorners, ParallelAndDistantPlanesGiveNoEdge) {
  const auto a = patch(kUtm, {3, 0, 0}, {0, 3, 0}, 5000, 4);
  const auto b = patch(kUtm + Eigen::Vector3d(0, 0, 0.5), {3, 0, 0}, {0, 3, 0}, 5000, 5);
  const auto far_wall = patch(kUtm + Eigen::Vector3d(10, 0, 1), {0, 3, 0}, {0, 0, 2}, 5000, 6);
  const std::vector<SegmentGeometry> segments{{fit(a), a}, {fit(b), b}, {fit(far_wall), far_wall}};
  const Features features = findEdgesAndCorners(segments);
  EXPECT_TRUE(features.edges.empty());
  EXPECT_TRUE(features.corners.empty());
}

}  // namespace
}  // namespace plumb::reco
