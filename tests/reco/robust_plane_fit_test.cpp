// The robust final fit's pieces (reco/robust_plane_fit.h): the biweight, the robust scale, and
// the weighted plane fit against PlaneRegression's.

#include "reco/robust_plane_fit.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <vector>

#include "engine/core/random.h"
#include "reco/plane_regression.h"

namespace plumb::reco {
namespace {

TEST(RobustPlaneFit, TheBiweightFallsFromOneToZeroAtTheWindow) {
  EXPECT_DOUBLE_EQ(biweight(0.0, 0.03), 1.0);
  EXPECT_DOUBLE_EQ(biweight(0.015, 0.03), 0.5625);  // (1 - 1/4)^2
  EXPECT_DOUBLE_EQ(biweight(-0.015, 0.03), 0.5625);
  EXPECT_DOUBLE_EQ(biweight(0.03, 0.03), 0.0);
  EXPECT_DOUBLE_EQ(biweight(0.5, 0.03), 0.0);
  EXPECT_DOUBLE_EQ(biweight(NAN, 0.03), 0.0);
}

TEST(RobustPlaneFit, TheRobustScaleIsTheNoiseEvenWithAFifthOfOutliers) {
  Random random(7);
  std::vector<double> clean, dirty;
  for (int i = 0; i < 20000; ++i) {
    const double d = std::abs(0.004 * random.gaussian());
    clean.push_back(d);
    dirty.push_back(i % 5 == 0 ? 0.5 + random.uniform() : d);
  }
  EXPECT_NEAR(robustScale(clean), 0.004, 0.004 * 0.03);
  // A fifth of the residuals far off moves the median to the 62.5th percentile of |x|: 0.89 sigma.
  EXPECT_NEAR(robustScale(dirty), 0.004 * 1.4826 * 0.887, 0.004 * 0.05);
  EXPECT_EQ(robustScale({}), 0.0);
}

// A 4 m x 2.5 m wall at UTM-like coordinates, 3 mm noise along its normal.
std::vector<Eigen::Vector3d> noisyWall(std::size_t count, std::uint64_t seed) {
  const Eigen::Vector3d origin(512000.0, 5403000.0, 250.0);
  const Eigen::Vector3d tangent = Eigen::Vector3d(0.8, 0.6, 0.0);
  const Eigen::Vector3d up(0.0, 0.0, 1.0);
  const Eigen::Vector3d normal = tangent.cross(up);
  Random random(seed);
  std::vector<Eigen::Vector3d> points;
  for (std::size_t i = 0; i < count; ++i) {
    points.push_back(origin + 4.0 * random.uniform() * tangent + 2.5 * random.uniform() * up +
                     0.003 * random.gaussian() * normal);
  }
  return points;
}

TEST(RobustPlaneFit, UnitWeightsGiveTheRegressionsPlane) {
  const std::vector<Eigen::Vector3d> points = noisyWall(5000, 3);
  PlaneRegression regression;
  for (const Eigen::Vector3d& p : points) regression.add(p);
  const Plane expected = regression.fit();
  const Plane fitted = fitWeightedPlane(points, std::vector<double>(points.size(), 1.0));
  ASSERT_TRUE(fitted.valid);
  EXPECT_NEAR(std::abs(fitted.normal.dot(expected.normal)), 1.0, 1e-12);
  EXPECT_LT((fitted.centroid - expected.centroid).norm(), 1e-9);
  EXPECT_NEAR(fitted.lambda2, expected.lambda2, expected.lambda2 * 1e-6);
  EXPECT_NEAR(fitted.rms, expected.rms, expected.rms * 1e-6);
  EXPECT_EQ(fitted.point_count, points.size());
}

TEST(RobustPlaneFit, PointsOfWeightZeroCountForNothing) {
  std::vector<Eigen::Vector3d> points = noisyWall(2000, 5);
  std::vector<double> weights(points.size(), 1.0);
  const Plane clean = fitWeightedPlane(points, weights);
  for (int i = 0; i < 100; ++i) {
    points.push_back(points[static_cast<std::size_t>(i)] + Eigen::Vector3d(0.0, 0.0, 3.0));
    weights.push_back(0.0);
  }
  const Plane with_ignored = fitWeightedPlane(points, weights);
  ASSERT_TRUE(with_ignored.valid);
  EXPECT_NEAR(std::abs(with_ignored.normal.dot(clean.normal)), 1.0, 1e-12);
  EXPECT_LT((with_ignored.centroid - clean.centroid).norm(), 1e-9);
  EXPECT_EQ(with_ignored.point_count, clean.point_count);
}

TEST(RobustPlaneFit, FewerThanThreeWeightedPointsGiveNoPlane) {
  const std::vector<Eigen::Vector3d> points = noisyWall(10, 9);
  std::vector<double> weights(points.size(), 0.0);
  weights[0] = weights[4] = 1.0;
  EXPECT_FALSE(fitWeightedPlane(points, weights).valid);
  EXPECT_FALSE(fitWeightedPlane({}, {}).valid);
  weights[7] = 0.5;
  EXPECT_TRUE(fitWeightedPlane(points, weights).valid);
}

}  // namespace
}  // namespace plumb::reco
