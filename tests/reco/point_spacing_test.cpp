#include "reco/point_spacing.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "reco/plane_regression.h"

namespace plumb::reco {
namespace {

// A floor patch of scan lines at UTM-like coordinates: `along` apart on a line, `across` between
// lines, `columns` x `rows` points.
std::vector<Eigen::Vector3d> scanLines(double along, double across, int columns, int rows) {
  const Eigen::Vector3d origin(512000.25, 5403000.5, 250.0);
  std::vector<Eigen::Vector3d> points;
  for (int row = 0; row < rows; ++row) {
    for (int column = 0; column < columns; ++column)
      points.push_back(origin + Eigen::Vector3d(column * along, row * across, 0));
  }
  return points;
}

Plane fitted(const std::vector<Eigen::Vector3d>& points) {
  PlaneRegression regression = PlaneRegression::withReference(points.front());
  for (const Eigen::Vector3d& p : points) regression.add(p);
  return regression.fit();
}

TEST(PointSpacing, NearestNeighbourSeesTheSpacingAlongTheLines) {
  const auto points = scanLines(0.01, 0.06, 60, 10);
  EXPECT_NEAR(medianNearestDistance(points, 0.5), 0.01, 1e-9);
  // Neighbours beyond the reach count as the reach.
  EXPECT_NEAR(medianNearestDistance(points, 0.005), 0.005, 1e-12);
}

TEST(PointSpacing, ArealSpacingAlsoSeesTheGapsBetweenLines) {
  const auto points = scanLines(0.01, 0.06, 60, 10);
  // The hull is 0.59 x 0.54 m over 600 points: sqrt(area / n), a little under sqrt(0.01 x 0.06)
  // because the hull ends at the outermost points.
  const double expected = std::sqrt(0.59 * 0.54 / 600.0);
  EXPECT_NEAR(arealSpacing(fitted(points), points), expected, 1e-6);
  EXPECT_GT(arealSpacing(fitted(points), points), 2.0 * medianNearestDistance(points, 0.5));
}

TEST(PointSpacing, ArealSpacingOfAQuarterDisc) {
  // The quarter of a wall next to a room corner, points on a 2 cm grid.
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i <= 50; ++i) {
    for (int j = 0; j <= 50; ++j) {
      if (i * i + j * j <= 50 * 50) points.emplace_back(0.02 * i, 0.0, 0.02 * j);
    }
  }
  EXPECT_NEAR(arealSpacing(fitted(points), points), 0.02, 0.002);
}

TEST(PointSpacing, ArealSpacingOfALargePatchFromItsOutermostPoints) {
  // 120,000 points on a 3 mm grid in a 0.897 x 1.197 m rectangle turned by 30 degrees in its
  // plane, so that the hull's strips cut its edges at a slant: its corners are points, its hull
  // is the rectangle.
  const Eigen::Vector3d origin(512000.25, 5403000.5, 250.0);
  const Eigen::Vector3d u(std::cos(0.5236), std::sin(0.5236), 0.0);
  const Eigen::Vector3d v(-std::sin(0.5236), std::cos(0.5236), 0.0);
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i < 300; ++i) {
    for (int j = 0; j < 400; ++j) points.push_back(origin + 0.003 * i * u + 0.003 * j * v);
  }
  const double expected = std::sqrt(0.897 * 1.197 / 120000.0);
  EXPECT_NEAR(arealSpacing(fitted(points), points), expected, 1e-3 * expected);
}

TEST(PointSpacing, NearestNeighboursBeyondTheFirstGuessAreFound) {
  // A cubic lattice of 2 cm, 125,000 points: the guess from the extent (four times diagonal /
  // sqrt(n)) is under 2 cm, so every sample looks again as far as the reach.
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i < 50; ++i) {
    for (int j = 0; j < 50; ++j) {
      for (int k = 0; k < 50; ++k) points.emplace_back(0.02 * i, 0.02 * j, 0.02 * k);
    }
  }
  EXPECT_NEAR(medianNearestDistance(points, 0.05), 0.02, 1e-9);
  EXPECT_NEAR(medianNearestDistance(points, 0.015), 0.015, 1e-12);
}

TEST(PointSpacing, DegenerateInputsHaveNoSpacing) {
  const std::vector<Eigen::Vector3d> one{{1, 2, 3}};
  EXPECT_EQ(medianNearestDistance(one, 1.0), 0.0);
  const std::vector<Eigen::Vector3d> line{{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {3, 0, 0}};
  Plane plane;
  plane.centroid = Eigen::Vector3d(1.5, 0, 0);
  plane.tangent = Eigen::Vector3d::UnitX();
  plane.bitangent = Eigen::Vector3d::UnitY();
  plane.normal = Eigen::Vector3d::UnitZ();
  EXPECT_EQ(arealSpacing(plane, line), 0.0);
  EXPECT_EQ(arealSpacing(plane, std::span(line).first(2)), 0.0);
  const std::vector<Eigen::Vector3d> same(10, Eigen::Vector3d(5, 5, 5));
  EXPECT_EQ(arealSpacing(plane, same), 0.0);
  EXPECT_EQ(medianNearestDistance(same, 1.0), 1.0);  // duplicates are no neighbours
}

}  // namespace
}  // namespace plumb::reco
