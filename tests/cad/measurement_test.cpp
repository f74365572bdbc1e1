#include "cad/measurement.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>

#include "tests/cad/sample_project.h"

namespace plumb::cad {
namespace {

using TermKind = MeasureTerm::Kind;

// At UTM coordinates, where a careless subtraction loses millimetres.
const Eigen::Vector3d kO = test::kOrigin;

MeasureTerm point(const Eigen::Vector3d& p) {
  return {TermKind::kPoint, kO + p, Eigen::Vector3d::Zero(), {}};
}
MeasureTerm plane(const Eigen::Vector3d& p, const Eigen::Vector3d& normal) {
  return {TermKind::kPlane, kO + p, normal.normalized(), {}};
}
MeasureTerm line(const Eigen::Vector3d& p, const Eigen::Vector3d& direction) {
  return {TermKind::kLine, kO + p, direction.normalized(), {}};
}

Eigen::Vector3d turned(const Eigen::Vector3d& v, double degrees, const Eigen::Vector3d& axis) {
  return Eigen::AngleAxisd(degrees * M_PI / 180.0, axis.normalized()) * v;
}

TEST(Measure, DistanceBetweenTwoPoints) {
  const MeasureValue d = measure(MeasureKind::kDistance, {point({1, 2, 3}), point({4, 6, 3})});
  EXPECT_NEAR(d.value, 5.0, 1e-9);
  EXPECT_NEAR((d.from - (kO + Eigen::Vector3d(1, 2, 3))).norm(), 0.0, 1e-9);
  EXPECT_EQ(measureText(MeasureKind::kDistance, d), "5.0000 m");
}

TEST(Measure, AnglesAreAcuteAndExactNearZeroAndNinety) {
  const MeasureTerm floor = plane({0, 0, 0}, Eigen::Vector3d::UnitZ());
  // A wall, whichever way its normal points.
  EXPECT_NEAR(measure(MeasureKind::kAngle, {floor, plane({1, 0, 1}, Eigen::Vector3d::UnitX())}).value, 90.0, 1e-12);
  EXPECT_NEAR(measure(MeasureKind::kAngle, {floor, plane({1, 0, 1}, -Eigen::Vector3d::UnitX())}).value, 90.0, 1e-12);
  // A roof at 30 degrees; and 150 degrees between normals is the same 30 degrees.
  const Eigen::Vector3d roof = turned(Eigen::Vector3d::UnitZ(), 30.0, Eigen::Vector3d::UnitY());
  EXPECT_NEAR(measure(MeasureKind::kAngle, {floor, plane({0, 0, 3}, roof)}).value, 30.0, 1e-9);
  EXPECT_NEAR(measure(MeasureKind::kAngle, {floor, plane({0, 0, 3}, -roof)}).value, 30.0, 1e-9);
  // A wall 0.01 degrees off square keeps its hundredth (acos would lose it near 90).
  const Eigen::Vector3d off = turned(Eigen::Vector3d::UnitX(), 0.01, Eigen::Vector3d::UnitY());
  EXPECT_NEAR(measure(MeasureKind::kAngle, {floor, plane({1, 0, 1}, off)}).value, 89.99, 1e-9);
  // A line and a plane: a stair's nosing line rising at 35 degrees against the floor.
  const Eigen::Vector3d rising = turned(Eigen::Vector3d::UnitX(), -35.0, Eigen::Vector3d::UnitY());
  EXPECT_NEAR(measure(MeasureKind::kAngle, {floor, line({0, 0, 0}, rising)}).value, 35.0, 1e-9);
  EXPECT_NEAR(measure(MeasureKind::kAngle, {line({0, 0, 0}, rising), floor}).value, 35.0, 1e-9);
  // Two lines: the edges of a room's corner.
  EXPECT_NEAR(
      measure(MeasureKind::kAngle, {line({0, 0, 0}, Eigen::Vector3d::UnitX()), line({0, 0, 0}, {1, 1, 0})}).value, 45.0,
      1e-9);
  EXPECT_EQ(measureText(MeasureKind::kAngle, measure(MeasureKind::kAngle, {floor, plane({0, 0, 3}, roof)})),
            "30.00\u00b0");
}

TEST(Measure, PointToPlaneDropsAPerpendicular) {
  const MeasureTerm wall = plane({2, 0, 0}, turned(Eigen::Vector3d::UnitX(), 20.0, Eigen::Vector3d::UnitZ()));
  const Eigen::Vector3d p = kO + Eigen::Vector3d(5, 3, 1);
  const MeasureValue d = measure(MeasureKind::kPointToPlane, {wall, point({5, 3, 1})});
  EXPECT_NEAR(d.value, std::abs(wall.direction.dot(p - wall.point)), 1e-9);
  EXPECT_NEAR((d.from - p).norm(), 0.0, 1e-12);
  EXPECT_NEAR(wall.direction.dot(d.to - wall.point), 0.0, 1e-9) << "the foot lies on the plane";
  EXPECT_NEAR((d.to - d.from).normalized().cross(wall.direction).norm(), 0.0, 1e-9) << "along the normal";
}

TEST(Measure, TheWidthOfARoomBetweenTwoWalls) {
  // Parallel walls 4.2 m apart, picked at points far apart along them: the width is still 4.2.
  const MeasureValue width = measure(MeasureKind::kBetweenPlanes, {plane({0, 1, 1}, Eigen::Vector3d::UnitX()),
                                                                   plane({4.2, 3, 2}, -Eigen::Vector3d::UnitX())});
  EXPECT_NEAR(width.value, 4.2, 1e-9);
  EXPECT_NEAR(*width.second, 0.0, 1e-9);
  EXPECT_NEAR(width.from.x() - kO.x(), 0.0, 1e-9);
  EXPECT_NEAR(width.to.x() - kO.x(), 4.2, 1e-9);
  EXPECT_NEAR(width.from.y() - kO.y(), 2.0, 1e-9) << "in the middle of the picked points";
  // One wall 0.5 degrees off: the width is taken in the middle of the picks, along the mean normal.
  const Eigen::Vector3d off = turned(-Eigen::Vector3d::UnitX(), 0.5, Eigen::Vector3d::UnitZ());
  const MeasureValue skew =
      measure(MeasureKind::kBetweenPlanes, {plane({0, 1, 1}, Eigen::Vector3d::UnitX()), plane({4.2, 3, 2}, off)});
  EXPECT_NEAR(*skew.second, 0.5, 1e-9);
  EXPECT_NEAR(skew.value, 4.2, 0.02);
  EXPECT_EQ(measureText(MeasureKind::kBetweenPlanes, width), "4.2000 m (0.00\u00b0 from parallel)");
  // Planes well off parallel have no distance apart.
  const auto problem = measureProblem(MeasureKind::kBetweenPlanes,
                                      {plane({0, 1, 1}, Eigen::Vector3d::UnitX()), plane({4, 3, 2}, {1, 1, 0})});
  ASSERT_TRUE(problem);
  EXPECT_EQ(*problem, "the planes are 45.00\u00b0 from parallel (at most 5.00\u00b0): measure their angle instead");
}

TEST(Measure, AHeightIsVerticalAboveTheFloorUnderThePoint) {
  // A floor sloping 2 degrees down along x (a ramp): under x = 3 it lies 3 tan 2deg lower.
  const Eigen::Vector3d normal = turned(Eigen::Vector3d::UnitZ(), 2.0, Eigen::Vector3d::UnitY());
  const MeasureTerm floor = plane({0, 0, 0}, normal);
  const MeasureValue h = measure(MeasureKind::kHeight, {floor, point({3, 1, 2.5})});
  const double floor_z = -3.0 * std::tan(2.0 * M_PI / 180.0);
  EXPECT_NEAR(h.value, 2.5 - floor_z, 1e-9);
  EXPECT_NEAR(h.from.x(), h.to.x(), 1e-12);
  EXPECT_NEAR(h.from.y(), h.to.y(), 1e-12);
  EXPECT_NEAR(h.from.z() - kO.z(), floor_z, 1e-9);
  // Below the floor is negative (a pit), whichever way the floor's normal points.
  EXPECT_NEAR(measure(MeasureKind::kHeight, {plane({0, 0, 0}, -Eigen::Vector3d::UnitZ()), point({1, 1, -0.75})}).value,
              -0.75, 1e-9);
  // A wall is no floor.
  const auto problem = measureProblem(MeasureKind::kHeight,
                                      {plane({0, 0, 0}, Eigen::Vector3d::UnitX()), point(Eigen::Vector3d::Zero())});
  ASSERT_TRUE(problem);
  EXPECT_NE(problem->find("the floor is tilted 90.00\u00b0 from level (at most 30.00\u00b0)"), std::string::npos);
}

TEST(Measure, AreaAndPerimeterOfAConcavePolygonAnywhere) {
  // An L of 1.5 m^2, perimeter 7 m, stood up in a wall at 40 degrees to x.
  std::vector<Eigen::Vector3d> ring;
  const Eigen::Matrix3d to_wall = Eigen::AngleAxisd(40.0 * M_PI / 180.0, Eigen::Vector3d::UnitZ()).toRotationMatrix() *
                                  Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitX()).toRotationMatrix();
  for (const auto& [u, v] :
       std::vector<std::pair<double, double>>{{0, 0}, {2, 0}, {2, 0.5}, {0.5, 0.5}, {0.5, 1.5}, {0, 1.5}}) {
    ring.push_back(kO + to_wall * Eigen::Vector3d(u, v, 0.0));
  }
  const MeasureValue a = measure(
      MeasureKind::kArea, {MeasureTerm{TermKind::kPolygon, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(), ring}});
  EXPECT_NEAR(a.value, 1.0 + 0.5, 1e-9);
  EXPECT_NEAR(*a.second, 2.0 + 0.5 + 1.5 + 1.0 + 0.5 + 1.5, 1e-9);
  EXPECT_EQ(measureText(MeasureKind::kArea, a), "1.500 m\u00b2 (perimeter 7.000 m)");
}

TEST(Measure, TheWrongTermsAreNamed) {
  EXPECT_EQ(measureProblem(MeasureKind::kDistance, {point(Eigen::Vector3d::Zero())}).value_or(""),
            "Distance takes 2 terms, not 1");
  EXPECT_EQ(measureProblem(MeasureKind::kAngle, {point(Eigen::Vector3d::Zero()), point(Eigen::Vector3d::Zero())})
                .value_or(""),
            "Angle: term 1 must be a plane or line, not a point");
  EXPECT_EQ(measureProblem(MeasureKind::kArea, {point(Eigen::Vector3d::Zero())}).value_or(""),
            "Area: term 1 must be a polygon, not a point");
  MeasureTerm bent = plane(Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitZ());
  bent.direction *= 1.01;
  EXPECT_NE(measureProblem(MeasureKind::kPointToPlane, {bent, point(Eigen::Vector3d::Zero())})
                .value_or("")
                .find("must be a unit vector"),
            std::string::npos);
  MeasureTerm lost = point(Eigen::Vector3d::Zero());
  lost.point.y() = std::nan("");
  EXPECT_EQ(measureProblem(MeasureKind::kDistance, {point(Eigen::Vector3d::Zero()), lost}).value_or(""),
            "term 2 (point): a coordinate is not finite");
  EXPECT_FALSE(measureProblem(MeasureKind::kDistance, {point(Eigen::Vector3d::Zero()), point(Eigen::Vector3d::Zero())}))
      << "a zero distance is a distance";
}

TEST(Measure, NamesReadBack) {
  for (const MeasureKind kind : {MeasureKind::kDistance, MeasureKind::kAngle, MeasureKind::kPointToPlane,
                                 MeasureKind::kBetweenPlanes, MeasureKind::kHeight, MeasureKind::kArea}) {
    EXPECT_EQ(measureKindNamed(measureKindName(kind)), kind);
  }
  for (const TermKind kind : {TermKind::kPoint, TermKind::kPlane, TermKind::kLine, TermKind::kPolygon}) {
    EXPECT_EQ(measureTermKindNamed(measureTermKindName(kind)), kind);
  }
  EXPECT_FALSE(measureKindNamed("volume"));
}

// The sample project's measurements (one of each kind) are what their names say.
TEST(Measure, TheSampleProjectsMeasurements) {
  const Project project = test::sampleProject();
  ASSERT_EQ(project.measurements.size(), 6u);
  for (const Measurement& m : project.measurements) ASSERT_FALSE(measureProblem(m.kind, m.terms)) << m.name;
  const auto value = [&](std::size_t i) {
    return measure(project.measurements[i].kind, project.measurements[i].terms);
  };
  EXPECT_NEAR(value(1).value, 90.0, 1e-9);    // wall x to the floor's edge along x
  EXPECT_NEAR(value(2).value, 3.9375, 1e-9);  // a point to wall x
  EXPECT_NEAR(value(3).value, 4.0, 1e-3);     // wall x to a wall 0.06 degrees off
  EXPECT_NEAR(value(4).value, 2.5, 1e-3);     // above the slightly tilted floor
  EXPECT_NEAR(value(5).value, 1.0, 1e-9);     // the L: 0.5 + 0.5 m^2
  EXPECT_NEAR(*value(5).second, 5.0, 1e-9);
}

}  // namespace
}  // namespace plumb::cad
