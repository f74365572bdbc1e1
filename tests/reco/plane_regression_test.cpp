// Incremental plane regression (paper section 3.2, appendix A) against a two-pass
// double-precision PCA of the same points.

#include "reco/plane_regression.h"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <cmath>
#include <vector>

#include "engine/core/random.h"

namespace plumb::reco {
namespace {

// A 5 m x 3 m wall at UTM-like coordinates, turned 37 degrees about the vertical and tilted
// slightly, with 1 mm Gaussian noise along its normal:
//
//        b (3 m, nearly vertical)
//        ^
//        |  . . . . . . . . .
//        |  . . . wall . . .      normal n out of the page
//        o----------------------> t (5 m, horizontal)
//   (512000, 5403000, 250)
struct Wall {
  Eigen::Vector3d origin{512000.0, 5403000.0, 250.0};
  Eigen::Vector3d tangent, bitangent, normal;
  std::vector<Eigen::Vector3d> points;
};

Wall makeWall(std::size_t count, double noise_m, std::uint64_t seed) {
  Wall wall;
  const double angle = 37.0 * M_PI / 180.0;
  wall.tangent = Eigen::Vector3d(std::cos(angle), std::sin(angle), 0.0);
  wall.bitangent = Eigen::Vector3d(0.02, -0.01, 1.0).normalized();
  wall.bitangent -= wall.bitangent.dot(wall.tangent) * wall.tangent;
  wall.bitangent.normalize();
  wall.normal = wall.tangent.cross(wall.bitangent);
  Random random(seed);
  wall.points.reserve(count);
  for (std::size_t i = 0; i < count; ++i) {
    wall.points.push_back(wall.origin + 5.0 * random.uniform() * wall.tangent +
                          3.0 * random.uniform() * wall.bitangent + noise_m * random.gaussian() * wall.normal);
  }
  return wall;
}

struct Pca {
  Eigen::Vector3d mean, normal;
  double lambda0, lambda1, lambda2;
};

// The textbook two-pass PCA: the mean first, then the covariance of the centred points.
Pca twoPassPca(const std::vector<Eigen::Vector3d>& points) {
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const auto& p : points) mean += p;
  mean /= static_cast<double>(points.size());
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (const auto& p : points) cov += (p - mean) * (p - mean).transpose();
  cov /= static_cast<double>(points.size() - 1);
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(cov);
  return {mean, solver.eigenvectors().col(0), solver.eigenvalues()(2), solver.eigenvalues()(1),
          solver.eigenvalues()(0)};
}

// Angle between two unsigned normals, accurate for tiny angles.
double angleBetween(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::atan2(a.cross(b).norm(), std::abs(a.dot(b)));
}

PlaneRegression regressionOf(const std::vector<Eigen::Vector3d>& points, PlaneRegression regression = {}) {
  for (const auto& p : points) regression.add(p);
  return regression;
}

constexpr double kNormalToleranceRad = 1e-6;
constexpr double kLambda2RelativeTolerance = 1e-4;

TEST(PlaneRegression, RebasedSumsMatchTwoPassPcaAtUtmCoordinates) {
  const Wall wall = makeWall(100'000, 0.001, 1);
  const Pca reference = twoPassPca(wall.points);
  const Plane plane = regressionOf(wall.points).fit();

  ASSERT_TRUE(plane.valid);
  EXPECT_LE(angleBetween(plane.normal, reference.normal), kNormalToleranceRad);
  EXPECT_LE(std::abs(plane.lambda2 - reference.lambda2) / reference.lambda2, kLambda2RelativeTolerance);
  EXPECT_NEAR(plane.lambda0, reference.lambda0, 1e-9 * reference.lambda0);
  EXPECT_NEAR(plane.lambda1, reference.lambda1, 1e-9 * reference.lambda1);
  // 10 nm: the reference mean itself sums raw UTM coordinates and rounds at the nanometre level.
  EXPECT_LE((plane.centroid - reference.mean).norm(), 1e-8);
  // And both against the truth the wall was made from: the noise alone limits the normal.
  EXPECT_LE(angleBetween(plane.normal, wall.normal), 1e-4);
  EXPECT_EQ(plane.point_count, 100'000u);
}

TEST(PlaneRegression, WithoutRebasingTheSameSumsLosePrecision) {
  // The paper's equation 1 taken literally: sums of raw coordinates (reference at the origin).
  const Wall wall = makeWall(100'000, 0.001, 1);
  const Pca reference = twoPassPca(wall.points);
  const Plane raw = regressionOf(wall.points, PlaneRegression::withReference(Eigen::Vector3d::Zero())).fit();

  // Squares of northings near 5.4e6 reach 2.9e13; their sum over 1e5 points rounds by far more
  // than the 1e-6 m^2 variance across the wall, so the plane is lost, not merely perturbed.
  const double lambda2_error = raw.valid ? std::abs(raw.lambda2 - reference.lambda2) / reference.lambda2 : INFINITY;
  const double normal_error = raw.valid ? angleBetween(raw.normal, reference.normal) : INFINITY;
  RecordProperty("raw_lambda2_relative_error", std::to_string(lambda2_error));
  RecordProperty("raw_normal_error_rad", std::to_string(normal_error));
  EXPECT_GT(lambda2_error, 100 * kLambda2RelativeTolerance);
  EXPECT_GT(normal_error, 100 * kNormalToleranceRad);
}

TEST(PlaneRegression, RebaseChangesTheSumsButNotThePlane) {
  const Wall wall = makeWall(10'000, 0.002, 2);
  PlaneRegression regression = regressionOf(wall.points);
  const Plane before = regression.fit();

  const Eigen::Vector3d new_reference = wall.origin + Eigen::Vector3d(2.5, -1.0, 1.5);
  regression.rebase(new_reference);
  const PlaneRegression direct = regressionOf(wall.points, PlaneRegression::withReference(new_reference));

  EXPECT_EQ(regression.reference(), new_reference);
  EXPECT_LE((regression.sum() - direct.sum()).norm(), 1e-6);
  EXPECT_LE((regression.sumSquares() - direct.sumSquares()).norm(), 1e-6);
  EXPECT_LE((regression.sumCross() - direct.sumCross()).norm(), 1e-6);
  const Plane after = regression.fit();
  EXPECT_LE(angleBetween(before.normal, after.normal), 1e-9);
  EXPECT_NEAR(before.lambda2, after.lambda2, 1e-6 * before.lambda2);
}

TEST(PlaneRegression, MergeEqualsAddingEveryPoint) {
  const Wall wall = makeWall(20'000, 0.002, 3);
  const std::vector<Eigen::Vector3d> first(wall.points.begin(), wall.points.begin() + 7'000);
  const std::vector<Eigen::Vector3d> second(wall.points.begin() + 7'000, wall.points.end());

  PlaneRegression merged = regressionOf(first);
  merged.merge(regressionOf(second));  // a different reference: the second half's first point
  const PlaneRegression whole = regressionOf(wall.points);

  EXPECT_EQ(merged.count(), whole.count());
  EXPECT_LE((merged.covariance() - whole.covariance()).norm(), 1e-9 * whole.covariance().norm());
  EXPECT_LE((merged.centroid() - whole.centroid()).norm(), 1e-9);
  const Plane a = merged.fit(), b = whole.fit();
  EXPECT_LE(angleBetween(a.normal, b.normal), 1e-9);
  EXPECT_NEAR(a.lambda2, b.lambda2, 1e-6 * b.lambda2);
}

TEST(PlaneRegression, MergeWithEmptyRegressions) {
  const Wall wall = makeWall(1'000, 0.002, 4);
  const PlaneRegression full = regressionOf(wall.points);

  PlaneRegression into_empty;
  into_empty.merge(full);
  EXPECT_EQ(into_empty.count(), full.count());
  EXPECT_EQ(into_empty.reference(), full.reference());

  PlaneRegression unchanged = full;
  unchanged.merge(PlaneRegression{});
  EXPECT_EQ(unchanged.count(), full.count());
  EXPECT_EQ(unchanged.sum(), full.sum());
}

TEST(PlaneRegression, FirstPointIsTheReference) {
  PlaneRegression regression;
  const Eigen::Vector3d first(512000.25, 5403000.5, 250.125);
  regression.add(first);
  regression.add(first + Eigen::Vector3d(1, 0, 0));
  EXPECT_EQ(regression.reference(), first);
  EXPECT_EQ(regression.sum(), Eigen::Vector3d(1, 0, 0));
}

TEST(PlaneRegression, FrameIsRightHandedAndFollowsTheSpread) {
  const Wall wall = makeWall(10'000, 0.001, 5);
  const Plane plane = regressionOf(wall.points).fit();
  ASSERT_TRUE(plane.valid);
  EXPECT_NEAR(plane.normal.norm(), 1.0, 1e-12);
  EXPECT_NEAR(plane.tangent.norm(), 1.0, 1e-12);
  EXPECT_NEAR(plane.bitangent.norm(), 1.0, 1e-12);
  EXPECT_LE((plane.tangent.cross(plane.bitangent) - plane.normal).norm(), 1e-12);
  // The 5 m side spreads more than the 3 m side.
  EXPECT_LE(angleBetween(plane.tangent, wall.tangent), 1e-2);
  EXPECT_GE(plane.lambda0, plane.lambda1);
  EXPECT_GE(plane.lambda1, plane.lambda2);
}

TEST(PlaneRegression, RmsAndDistancesMatchTheNoise) {
  const Wall wall = makeWall(50'000, 0.003, 6);
  const Plane plane = regressionOf(wall.points).fit();
  ASSERT_TRUE(plane.valid);
  EXPECT_NEAR(plane.rms, 0.003, 0.003 * 0.02);
  double sum_squares = 0.0;
  for (const auto& p : wall.points) sum_squares += plane.signedDistance(p) * plane.signedDistance(p);
  EXPECT_NEAR(plane.rms, std::sqrt(sum_squares / static_cast<double>(wall.points.size())), 1e-9);

  const Eigen::Vector3d off_plane = plane.centroid + 0.005 * plane.normal + 1.0 * plane.tangent;
  EXPECT_NEAR(plane.distance(off_plane), 0.005, 1e-9);
  EXPECT_NEAR(plane.normal.dot(off_plane) + plane.offset, 0.005, 1e-6);  // offset form, UTM scale
  const Plane oriented = plane.orientedTowards(plane.centroid - plane.normal);
  EXPECT_LT(oriented.signedDistance(off_plane), 0.0);
}

TEST(PlaneRegression, ExactPlaneHasZeroVarianceNotNegative) {
  PlaneRegression regression;
  for (int i = 0; i < 50; ++i) {
    for (int j = 0; j < 50; ++j) regression.add({512000.0 + 0.1 * i, 5403000.0 + 0.1 * j, 250.0});
  }
  const Plane plane = regression.fit();
  ASSERT_TRUE(plane.valid);
  EXPECT_GE(plane.lambda2, 0.0);
  EXPECT_LE(plane.lambda2, 1e-20);
  EXPECT_NEAR(std::abs(plane.normal.z()), 1.0, 1e-12);
}

void expectInvalidAndFinite(const Plane& plane) {
  EXPECT_FALSE(plane.valid);
  EXPECT_TRUE(plane.normal.allFinite() && plane.tangent.allFinite() && plane.bitangent.allFinite() &&
              plane.centroid.allFinite());
  EXPECT_TRUE(std::isfinite(plane.offset) && std::isfinite(plane.lambda0) && std::isfinite(plane.lambda1) &&
              std::isfinite(plane.lambda2) && std::isfinite(plane.rms));
}

TEST(PlaneRegression, DegenerateInputGivesAnInvalidPlaneNeverNaN) {
  const Eigen::Vector3d utm(512000.0, 5403000.0, 250.0);
  expectInvalidAndFinite(PlaneRegression{}.fit());

  PlaneRegression two;
  two.add(utm);
  expectInvalidAndFinite(two.fit());
  two.add(utm + Eigen::Vector3d(1, 2, 3));
  expectInvalidAndFinite(two.fit());

  PlaneRegression collinear;
  for (int i = 0; i < 1000; ++i) collinear.add(utm + i * 0.01 * Eigen::Vector3d(0.6, 0.8, 0.0));
  expectInvalidAndFinite(collinear.fit());

  PlaneRegression duplicates;
  for (int i = 0; i < 1000; ++i) duplicates.add(utm);
  expectInvalidAndFinite(duplicates.fit());

  // Three points that do span a plane are enough.
  PlaneRegression triangle;
  triangle.add(utm);
  triangle.add(utm + Eigen::Vector3d(1, 0, 0));
  triangle.add(utm + Eigen::Vector3d(0, 1, 0));
  EXPECT_TRUE(triangle.fit().valid);
}

}  // namespace
}  // namespace plumb::reco
