#include "reco/ransac.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>

#include "engine/core/random.h"

namespace plumb::reco {
namespace {

double angleBetween(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::atan2(a.cross(b).norm(), std::abs(a.dot(b)));
}

//   z
//   |     .  outliers scattered in the box above
//   |   .
//   +==================== x    a floor z = 250 (UTM-like x, y), 2 mm noise, 70 % of the points
TEST(Ransac, FindsTheFloorAmongOutliers) {
  Random random(3);
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i < 7000; ++i) {
    points.emplace_back(512000.0 + 4.0 * random.uniform(), 5403000.0 + 4.0 * random.uniform(),
                        250.0 + 0.002 * random.gaussian());
  }
  for (int i = 0; i < 3000; ++i) {
    points.emplace_back(512000.0 + 4.0 * random.uniform(), 5403000.0 + 4.0 * random.uniform(),
                        250.05 + 2.0 * random.uniform());
  }
  std::vector<std::uint32_t> all(points.size());
  for (std::uint32_t i = 0; i < all.size(); ++i) all[i] = i;
  const PlaneSampleModel model(points);
  RansacOptions options;
  options.threshold = 0.01;
  Random draws(1);
  const auto result = ransacPlane(model, all, options, draws);
  ASSERT_TRUE(result.has_value());
  EXPECT_LE(angleBetween(result->plane.normal, Eigen::Vector3d::UnitZ()), 0.5 * M_PI / 180.0);
  EXPECT_NEAR(result->plane.centroid.z(), 250.0, 0.001);
  EXPECT_GE(result->inliers.size(), 6900u);
  EXPECT_LE(result->inliers.size(), 7100u);
  EXPECT_LT(result->iterations, options.max_iterations) << "the adaptive stop should end well before the cap";

  Random again(1);
  const auto repeat = ransacPlane(model, all, options, again);
  ASSERT_TRUE(repeat.has_value());
  EXPECT_EQ(repeat->inliers, result->inliers) << "the same seed gives the same plane";
}

//   z                  x = 2: 280 points spread evenly over the whole window (+-3 cm), as the
//   |                  strips of two walls along their edge lie about a plane slanted across it
//   |                  |
//   +=========== x     z = 0: 200 points with 1 mm noise
// Counting inliers takes the slab, which has more; MSAC takes the plane whose points lie close.
TEST(Ransac, MsacPrefersTheTightPlaneToAFullerLooseSlab) {
  Random random(4);
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i < 200; ++i) points.emplace_back(random.uniform(), random.uniform(), 0.001 * random.gaussian());
  for (int i = 0; i < 280; ++i) {
    points.emplace_back(2.0 + 0.06 * (random.uniform() - 0.5), random.uniform(), random.uniform());
  }
  std::vector<std::uint32_t> all(points.size());
  for (std::uint32_t i = 0; i < all.size(); ++i) all[i] = i;
  const PlaneSampleModel model(points);
  RansacOptions options;
  options.threshold = 0.03;
  options.confidence = 0.9999;  // both planes are sampled, whichever the score

  options.score = RansacScore::kInlierCount;
  Random counting(1);
  const auto slab = ransacPlane(model, all, options, counting);
  ASSERT_TRUE(slab.has_value());
  EXPECT_LE(angleBetween(slab->plane.normal, Eigen::Vector3d::UnitX()), 2.0 * M_PI / 180.0);

  options.score = RansacScore::kTruncatedSquares;
  Random msac(1);
  const auto tight = ransacPlane(model, all, options, msac);
  ASSERT_TRUE(tight.has_value());
  EXPECT_LE(angleBetween(tight->plane.normal, Eigen::Vector3d::UnitZ()), 2.0 * M_PI / 180.0);
  EXPECT_GE(tight->inliers.size(), 195u);
}

TEST(Ransac, CollinearOrTooFewPointsGiveNoPlane) {
  std::vector<Eigen::Vector3d> line;
  for (int i = 0; i < 100; ++i) line.emplace_back(512000.0 + 0.01 * i, 5403000.0 + 0.02 * i, 250.0);
  std::vector<std::uint32_t> all(line.size());
  for (std::uint32_t i = 0; i < all.size(); ++i) all[i] = i;
  const PlaneSampleModel model(line);
  Random random(1);
  EXPECT_FALSE(ransacPlane(model, all, {}, random).has_value());
  EXPECT_FALSE(ransacPlane(model, std::span(all).first(2), {}, random).has_value());
}

TEST(PlaneSampleModel, ThreePointPlanesAreExactAtUtmCoordinates) {
  const std::vector<Eigen::Vector3d> points{
      {512000.0, 5403000.0, 250.0}, {512001.0, 5403000.0, 250.0}, {512000.0, 5403001.0, 250.001}};
  const PlaneSampleModel model(points);
  const auto plane = model.fromSample({0, 1, 2});
  ASSERT_TRUE(plane.has_value());
  for (const auto& p : points) EXPECT_LT(plane->distance(p), 1e-9);
  EXPECT_FALSE(model.fromSample({0, 0, 1}).has_value());
}

}  // namespace
}  // namespace plumb::reco
