// The splat's surfels (engine/render/surfels.h) and their scales (splat_spacing.h), on the CPU:
// normals and spacings of known point patterns, and the density arithmetic of the octree's levels.

#include "engine/render/surfels.h"

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cmath>
#include <vector>

#include "engine/render/splat_spacing.h"

namespace plumb::render {
namespace {

lod::PackedPoint at(const Eigen::Vector3d& p) {
  return {static_cast<float>(p.x()), static_cast<float>(p.y()), static_cast<float>(p.z()), {0, 0, 0}, 0};
}

Eigen::Vector3f normalOf(const Surfel& surfel) {
  Eigen::Vector3f n;
  decodeNormal(surfel.normal, n.x(), n.y(), n.z());
  return n;
}

// Points on a grid of `step` in the plane through `centre` spanned by u and v, `rows` x `columns`.
std::vector<lod::PackedPoint> gridPlane(const Eigen::Vector3d& centre, const Eigen::Vector3d& u,
                                        const Eigen::Vector3d& v, double u_step, double v_step, int rows, int columns) {
  std::vector<lod::PackedPoint> points;
  for (int r = 0; r < rows; ++r) {
    for (int c = 0; c < columns; ++c) {
      points.push_back(at(centre + (c - columns / 2) * u_step * u + (r - rows / 2) * v_step * v));
    }
  }
  return points;
}

TEST(Surfels, NormalsSurviveTheirEncoding) {
  for (const Eigen::Vector3f& n :
       {Eigen::Vector3f(0, 0, 1), Eigen::Vector3f(0, 0, -1), Eigen::Vector3f(1, 0, 0),
        Eigen::Vector3f(0.3f, -0.8f, 0.52f).normalized(), Eigen::Vector3f(-0.6f, -0.2f, -0.77f).normalized()}) {
    const std::uint32_t packed = encodeNormal(n.x(), n.y(), n.z());
    EXPECT_NE(packed, kFacingTheEye);
    Eigen::Vector3f back;
    decodeNormal(packed, back.x(), back.y(), back.z());
    EXPECT_GT(back.dot(n), std::cos(1e-3f)) << n.transpose() << " came back as " << back.transpose();
  }
}

TEST(Surfels, APlaneGivesItsNormalAndItsSpacing) {
  const Eigen::Vector3d normal = Eigen::Vector3d(0.2, -0.4, 1.0).normalized();
  const Eigen::Vector3d u = normal.unitOrthogonal(), v = normal.cross(u);
  const std::vector<lod::PackedPoint> points = gridPlane({1.0, 1.0, 1.0}, u, v, 0.02, 0.02, 40, 40);
  const std::vector<Surfel> surfels = estimateSurfels(points, {}, 2.0, 0.25);
  ASSERT_EQ(surfels.size(), points.size());
  // The 4th nearest on a square grid: the 4 at one step; along an edge, 3 there and the 4th
  // diagonal (2.8 cm); at a corner, two steps away (4 cm).
  int one_step = 0;
  for (const Surfel& s : surfels) {
    EXPECT_GT(std::abs(normalOf(s).dot(normal.cast<float>())), 0.999f);
    EXPECT_GE(s.radius_m, 0.0199f);
    EXPECT_LE(s.radius_m, 0.0401f);
    if (s.radius_m < 0.0201f) ++one_step;
  }
  EXPECT_EQ(one_step, 38 * 38);
}

// A scanner's lines far apart on a wall: the nearest 12 of a point lie along its own line, the
// wider look finds the next lines and the plane.
TEST(Surfels, LinesFarApartStillSpanTheirPlane) {
  const std::vector<lod::PackedPoint> points =
      gridPlane({1.0, 1.0, 1.0}, Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitZ(), 0.08, 0.008, 100, 12);
  const std::vector<Surfel> surfels = estimateSurfels(points, {}, 2.0, 0.25);
  int planar = 0;
  for (const Surfel& s : surfels) {
    if (s.normal != kFacingTheEye && std::abs(normalOf(s).y()) > 0.999f) ++planar;
  }
  EXPECT_GT(planar, static_cast<int>(0.95 * static_cast<double>(points.size())));
}

TEST(Surfels, ALineAloneFacesTheEyeAndALonePointIsOnePixel) {
  std::vector<lod::PackedPoint> points;
  for (int i = 0; i < 50; ++i) points.push_back(at({0.5 + 0.01 * i, 1.0, 1.0}));
  points.push_back(at({1.8, 1.8, 1.8}));
  const std::vector<Surfel> surfels = estimateSurfels(points, {}, 2.0, 0.25);
  EXPECT_EQ(surfels[25].normal, kFacingTheEye);
  EXPECT_NEAR(surfels[25].radius_m, 0.5 * 0.02, 1e-4);  // half the 4th nearest: beside a line's end
  EXPECT_EQ(surfels.back().radius_m, 0.0f);
}

TEST(SplatSpacing, OctantsSplitAtTheNodesCentre) {
  const std::vector<lod::PackedPoint> points{at({0.1, 0.1, 0.1}), at({0.9, 0.1, 0.1}), at({0.1, 0.9, 0.9}),
                                             at({0.5, 0.5, 0.5}), at({0.49, 0.49, 0.49})};
  const std::array<std::uint32_t, 8> counts = countOctants(points, 0.5f);
  EXPECT_EQ(counts, (std::array<std::uint32_t, 8>{2, 1, 0, 0, 0, 0, 1, 1}));
}

// A parent with 300 points in octant 5 and 600 elsewhere, its child there drawn with 1,200:
// where the child is finest, its discs were measured among the drawn cloud (its points and its
// ancestors'); the parent's points in that octant, measured among the parent's and its
// parent's (300 x 5/4), shrink by sqrt(375 / 1575); its other octants keep their spacing.
TEST(SplatSpacing, ScalesFollowTheDrawnDensity) {
  const lod::CellKey root{0, 0, 0, 0};
  DrawnNode parent{root.child(3), 900, {100, 100, 100, 100, 100, 300, 50, 50}};
  DrawnNode child{root.child(3).child(5), 1200, {150, 150, 150, 150, 150, 150, 150, 150}};
  const std::vector<std::array<float, 8>> scales = octantRadiusScales(std::vector<DrawnNode>{parent, child});
  ASSERT_EQ(scales.size(), 2u);
  for (int o = 0; o < 8; ++o) {
    const float expected = o == 5 ? std::sqrt(375.0f / 1575.0f) : 1.0f;
    EXPECT_NEAR(scales[0][static_cast<std::size_t>(o)], expected, 1e-6) << "parent octant " << o;
    EXPECT_NEAR(scales[1][static_cast<std::size_t>(o)], 1.0f, 1e-6) << "child octant " << o;
  }
}

}  // namespace
}  // namespace plumb::render
