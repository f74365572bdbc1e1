// The interior of a planar point set (reco/interior_points.h).

#include "reco/interior_points.h"

#include <gtest/gtest.h>

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

TEST(InteriorPoints, NoPointsOrNoPlaneGiveNoInterior) {
  EXPECT_TRUE(interiorPoints(Plane{}, std::vector<Eigen::Vector3d>{}, 0.1).empty());
  const std::vector<Eigen::Vector3d> three{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  const std::vector<bool> none = interiorPoints(Plane{}, three, 0.1);
  EXPECT_EQ(none, std::vector<bool>(3, false));
}

}  // namespace
}  // namespace plumb::reco
