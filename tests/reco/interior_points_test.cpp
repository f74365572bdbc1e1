// The interior of a planar point set (reco/interior_points.h).

#include "reco/interior_points.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "engine/core/random.h"
#include "reco/plane_regression.h"

namespace plumb::reco {
namespace {

Plane planeOf(const std::vector<Eigen::Vector3d>& points) {
  PlaneRegression regression;
  for (const Eigen::Vector3d& p : points) regression.add(p);
  return regression.fit();
}

//   +--------------------------------+   a 2 x 1 m patch of random points (spacing about 1 cm)
//   |  border: the outermost cells   |   with a 0.4 x 0.4 m hole in the middle, a 2 cm step.
//   |   +--------+--+----------+     |   The outermost occupied cells, along the outline and the
//   |   |        |  | interior |     |   hole, are border: a band up to a step wide (the cells
//   |   |        +--+          |     |   fall where they fall). Points beyond 2.5 steps are all
//   |   +----------------------+     |   interior: the cells that missed a point by chance there
//   +--------------------------------+   (one in seventy) are filled by the closing.
TEST(InteriorPoints, TheBorderBandFollowsTheOutlineAndTheHoles) {
  Random random(3);
  std::vector<Eigen::Vector3d> points;
  while (points.size() < 20'000) {
    const double x = 2.0 * random.uniform(), y = random.uniform();
    if (x > 0.8 && x < 1.2 && y > 0.3 && y < 0.7) continue;  // the hole, in the middle
    points.emplace_back(x, y, 0.001 * random.gaussian());
  }
  const Plane plane = planeOf(points);
  constexpr double kStep = 0.02;  // about four points a cell: one in seventy empty by chance
  const std::vector<bool> interior = interiorPoints(plane, points, kStep);
  ASSERT_EQ(interior.size(), points.size());
  std::size_t wrong_far = 0, wrong_near = 0, far = 0, near = 0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const double x = points[i].x(), y = points[i].y();
    // Distance to the outline and to the hole's border. The raster lies along the plane's
    // tangent, which the random points turn by a milliradian or so from x.
    const double to_outline = std::min({x, 2.0 - x, y, 1.0 - y});
    const double to_hole = std::max({0.8 - x, x - 1.2, 0.3 - y, y - 0.7});
    const double to_border = std::min(to_outline, to_hole);
    if (to_border > 2.5 * kStep) {
      ++far;
      if (!interior[i]) ++wrong_far;
    } else if (to_border < 0.5 * kStep) {
      ++near;
      if (interior[i]) ++wrong_near;
    }
  }
  EXPECT_GT(far, 10'000u);
  EXPECT_GT(near, 500u);
  // Far from the border a point is interior unless its 3 x 3 cells missed every point together.
  EXPECT_LT(static_cast<double>(wrong_far), 0.001 * static_cast<double>(far));
  // Within half a step of the border a point is in the outermost cells unless those hold only a
  // sliver of the patch: three in four on average.
  EXPECT_LT(static_cast<double>(wrong_near), 0.4 * static_cast<double>(near));
}

//   +--------------------------------+   a 2 x 1 m wall of random points (spacing about 7 mm),
//   |                                |   20 mm of noise, tilted by 0.1 degrees (1.7 mm off at
//   |          wall                  |   its ends: what a plane a little off leaves); along its
//   |                                |   foot, y < 0, the strip of a floor that meets it: points
//   +================================+   0 to 70 mm in front of it (the window), 15 mm either side.
// The strip's cells are one-sided and left out; the wall's own cells are not, except along the
// foot where they share cells with the strip, and not at its far ends, which the tilt moves.
TEST(InteriorPoints, OneSidedBorderCellsAreTheStripOfAMeetingSurface) {
  Random random(5);
  const double tilt = 0.1 * M_PI / 180.0;
  std::vector<Eigen::Vector3d> points;
  std::vector<bool> strip;
  while (points.size() < 40'000) {
    const double x = 2.0 * random.uniform(), y = random.uniform();
    points.emplace_back(x, y, tilt * (x - 1.0) + 0.02 * random.gaussian());
    strip.push_back(false);
  }
  while (points.size() < 42'000) {
    points.emplace_back(2.0 * random.uniform(), 0.015 * random.gaussian(), 0.07 * random.uniform());
    strip.push_back(true);
  }
  // The plane without the tilt: the wall's points lean away from it at the ends.
  PlaneRegression wall;
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (!strip[i]) wall.add(points[i] - Eigen::Vector3d(0, 0, tilt * (points[i].x() - 1.0)));
  }
  const Plane plane = wall.fit();
  // Cells of 4 cm hold about 30 points, a neighbourhood 270: a standard error of 1.2 mm.
  constexpr double kStep = 0.04, kSigma = 0.02;
  const std::vector<bool> one_sided =
      oneSidedBorderPoints(borderRaster(plane, points, kStep), plane, points, 4, kSigma, 3.0, 0.25 * kSigma);
  ASSERT_EQ(one_sided.size(), points.size());
  std::size_t strip_out = 0, strip_count = 0, wall_out = 0, wall_away_from_foot = 0, wall_out_away = 0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (strip[i]) {
      ++strip_count;
      strip_out += one_sided[i] ? 1u : 0u;
      continue;
    }
    wall_out += one_sided[i] ? 1u : 0u;
    if (points[i].y() > 0.1) {
      ++wall_away_from_foot;
      wall_out_away += one_sided[i] ? 1u : 0u;
    }
  }
  std::printf("strip %zu of %zu out, wall %zu out (%zu of %zu away from the foot)\n", strip_out, strip_count, wall_out,
              wall_out_away, wall_away_from_foot);
  EXPECT_GT(static_cast<double>(strip_out), 0.9 * static_cast<double>(strip_count));
  // The wall loses its cells along the foot that the strip shares, about a tenth of its height.
  EXPECT_LT(static_cast<double>(wall_out), 0.12 * 40'000.0);
  // Away from the foot, at the far ends the tilt moves, the wall keeps (nearly) everything.
  EXPECT_LT(static_cast<double>(wall_out_away), 0.01 * static_cast<double>(wall_away_from_foot));
}

TEST(InteriorPoints, NoPointsOrNoPlaneGiveNoInterior) {
  EXPECT_TRUE(interiorPoints(Plane{}, std::vector<Eigen::Vector3d>{}, 0.1).empty());
  const std::vector<Eigen::Vector3d> three{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  const std::vector<bool> none = interiorPoints(Plane{}, three, 0.1);
  EXPECT_EQ(none, std::vector<bool>(3, false));
}

}  // namespace
}  // namespace plumb::reco
