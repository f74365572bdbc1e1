#include "reco/outline.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <numbers>
#include <set>
#include <utility>
#include <vector>

#include "engine/core/random.h"

namespace plumb::reco {
namespace {

constexpr double kCell = 0.01;
constexpr double kAlpha = 0.05;
constexpr double kSpacing = 0.004;  // below the cell, so a dense fill occupies every cell
// The boundary runs through the centres of the outermost cells, so it strays up to a cell from
// the shape's edge: the area by up to a cell times the perimeter.
constexpr double kEdgeTolerance = 1.5 * kCell;
constexpr double kAreaRounding = 1e-9;  // m^2: triangles against rings, the same lattice twice
constexpr double kOnBoundary = 1e-9;    // m: a triangle vertex on a ring

using Ring = std::vector<Eigen::Vector2d>;

// Points every kSpacing over [x0, x1] x [y0, y1] (ends included) where `keep` holds.
std::vector<Eigen::Vector2d> fill(double x0, double y0, double x1, double y1,
                                  const std::function<bool(const Eigen::Vector2d&)>& keep = nullptr) {
  std::vector<Eigen::Vector2d> points;
  const int nx = static_cast<int>(std::lround((x1 - x0) / kSpacing));
  const int ny = static_cast<int>(std::lround((y1 - y0) / kSpacing));
  for (int j = 0; j <= ny; ++j) {
    for (int i = 0; i <= nx; ++i) {
      const Eigen::Vector2d p(x0 + (x1 - x0) * i / nx, y0 + (y1 - y0) * j / ny);
      if (!keep || keep(p)) points.push_back(p);
    }
  }
  return points;
}

Outline outline(const std::vector<Eigen::Vector2d>& points, double alpha = kAlpha) {
  OutlineOptions options;
  options.alpha_m = alpha;
  options.cell_m = kCell;
  return outlineOf(points, options);
}

double signedArea(const Ring& ring) {
  double twice = 0.0;
  for (std::size_t k = 0; k < ring.size(); ++k) {
    const Eigen::Vector2d& a = ring[k];
    const Eigen::Vector2d& b = ring[(k + 1) % ring.size()];
    twice += a.x() * b.y() - a.y() * b.x();
  }
  return 0.5 * twice;
}

double ringArea(const Outline& o) {
  double area = 0.0;
  for (const Ring& ring : o.rings) area += signedArea(ring);
  return area;
}

std::size_t countRings(const Outline& o, bool holes) {
  std::size_t count = 0;
  for (const Ring& ring : o.rings) count += (signedArea(ring) < 0.0) == holes;
  return count;
}

// Plain doubles here and in winding(): these loops dominate the test's time in Debug builds.
double segmentDistance(double px, double py, double ax, double ay, double bx, double by) {
  const double abx = bx - ax, aby = by - ay;
  const double t = std::clamp(((px - ax) * abx + (py - ay) * aby) / (abx * abx + aby * aby), 0.0, 1.0);
  return std::hypot(ax + t * abx - px, ay + t * aby - py);
}

double segmentDistance(const Eigen::Vector2d& p, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return segmentDistance(p.x(), p.y(), a.x(), a.y(), b.x(), b.y());
}

double boundaryDistance(const Outline& o, const Eigen::Vector2d& p) {
  double best = INFINITY;
  for (const Ring& ring : o.rings) {
    const double* xy = ring.data()->data();
    const std::size_t n = ring.size();
    for (std::size_t k = 0; k < n; ++k) {
      const std::size_t l = k + 1 == n ? 0 : k + 1;
      best = std::min(best, segmentDistance(p.x(), p.y(), xy[2 * k], xy[2 * k + 1], xy[2 * l], xy[2 * l + 1]));
    }
  }
  return best;
}

// Winding number over all rings: 1 inside the region, 0 outside (holes wind back to 0).
int winding(const Outline& o, const Eigen::Vector2d& p) {
  int w = 0;
  for (const Ring& ring : o.rings) {
    const double* xy = ring.data()->data();
    const std::size_t n = ring.size();
    for (std::size_t k = 0; k < n; ++k) {
      const std::size_t l = k + 1 == n ? 0 : k + 1;
      const double ax = xy[2 * k], ay = xy[2 * k + 1], bx = xy[2 * l], by = xy[2 * l + 1];
      if ((ay <= p.y()) == (by <= p.y())) continue;  // does not span p's height
      const double side = (bx - ax) * (p.y() - ay) - (p.x() - ax) * (by - ay);
      if (ay <= p.y() && side > 0) ++w;
      if (ay > p.y() && side < 0) --w;
    }
  }
  return w;
}

bool inside(const Outline& o, const Eigen::Vector2d& p) {
  return winding(o, p) == 1;
}

// The invariants every outline keeps: rings simple and clean, triangles CCW inside the region
// and covering exactly the area the rings enclose.
void expectConsistent(const Outline& o) {
  std::set<std::pair<double, double>> seen;
  for (const Ring& ring : o.rings) {
    ASSERT_GE(ring.size(), 3u);
    for (std::size_t k = 0; k < ring.size(); ++k) {
      const Eigen::Vector2d& a = ring[(k + ring.size() - 1) % ring.size()];
      const Eigen::Vector2d& b = ring[k];
      const Eigen::Vector2d& c = ring[(k + 1) % ring.size()];
      EXPECT_TRUE(seen.insert({b.x(), b.y()}).second) << "vertex repeated at " << b.transpose();
      const Eigen::Vector2d u = b - a, v = c - b;
      EXPECT_GT(std::abs(u.x() * v.y() - u.y() * v.x()), 1e-12) << "collinear vertex at " << b.transpose();
    }
  }
  // No two ring edges cross or touch, apart from neighbours sharing their vertex.
  std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>> edges;
  for (const Ring& ring : o.rings) {
    for (std::size_t k = 0; k < ring.size(); ++k) edges.emplace_back(ring[k], ring[(k + 1) % ring.size()]);
  }
  const auto left = [](const auto& edge) { return std::min(edge.first.x(), edge.second.x()); };
  std::sort(edges.begin(), edges.end(), [&](const auto& e, const auto& f) { return left(e) < left(f); });
  for (std::size_t e = 0; e < edges.size(); ++e) {
    const double right = std::max(edges[e].first.x(), edges[e].second.x());
    for (std::size_t f = e + 1; f < edges.size() && left(edges[f]) <= right + kOnBoundary; ++f) {
      const auto& [a, b] = edges[e];
      const auto& [c, d] = edges[f];
      if (b == c || d == a) continue;
      const double gap = std::min(
          {segmentDistance(a, c, d), segmentDistance(b, c, d), segmentDistance(c, a, b), segmentDistance(d, a, b)});
      const auto cross = [](const Eigen::Vector2d& p, const Eigen::Vector2d& q, const Eigen::Vector2d& r) {
        return (q.x() - p.x()) * (r.y() - p.y()) - (q.y() - p.y()) * (r.x() - p.x());
      };
      const bool crossing = cross(a, b, c) * cross(a, b, d) < 0 && cross(c, d, a) * cross(c, d, b) < 0;
      EXPECT_TRUE(gap > kOnBoundary && !crossing) << "ring edges meet near " << a.transpose();
    }
  }
  double triangle_area = 0.0;
  for (const auto& t : o.triangles) {
    for (const std::uint32_t index : t) ASSERT_LT(index, o.vertices.size());
    const Eigen::Vector2d ab = o.vertices[t[1]] - o.vertices[t[0]];
    const Eigen::Vector2d ac = o.vertices[t[2]] - o.vertices[t[0]];
    const double area = 0.5 * (ab.x() * ac.y() - ab.y() * ac.x());
    EXPECT_GT(area, 0.0) << "triangle not counter-clockwise";
    triangle_area += area;
    const Eigen::Vector2d centroid = (o.vertices[t[0]] + o.vertices[t[1]] + o.vertices[t[2]]) / 3.0;
    EXPECT_TRUE(inside(o, centroid)) << "triangle outside the region at " << centroid.transpose();
  }
  for (const Eigen::Vector2d& v : o.vertices) {
    EXPECT_TRUE(inside(o, v) || boundaryDistance(o, v) < kOnBoundary) << "vertex outside at " << v.transpose();
  }
  EXPECT_NEAR(triangle_area, o.area_m2, kAreaRounding);
  EXPECT_NEAR(ringArea(o), o.area_m2, kAreaRounding);
}

// +----------+
// |##########|
// |##########|  1 m x 1 m, dense
// |##########|
// +----------+
TEST(Outline, DenseSquareIsOneCounterClockwiseRing) {
  const Outline o = outline(fill(0, 0, 1, 1));
  ASSERT_EQ(o.rings.size(), 1u);
  EXPECT_GT(signedArea(o.rings[0]), 0.0);
  EXPECT_NEAR(o.area_m2, 1.0, 4 * kEdgeTolerance);
  EXPECT_EQ(o.cell_m, kCell);
  for (const Eigen::Vector2d& v : o.rings[0]) {
    const double to_edge = std::min({std::abs(v.x()), std::abs(v.x() - 1), std::abs(v.y()), std::abs(v.y() - 1)});
    EXPECT_LT(to_edge, kEdgeTolerance) << v.transpose();
  }
  EXPECT_LE(o.rings[0].size(), 8u);  // four sides and four 45-degree corner cuts, nothing between
  expectConsistent(o);
}

// +----------+
// |##########|
// |###+--+###|  a 0.3 m hole, wider than 2 alpha: stays open, its corners filleted by alpha
// |###|  |###|
// |###+--+###|
// |##########|
// +----------+
TEST(Outline, WideHoleStaysOpenAsClockwiseRing) {
  const auto hole = [](const Eigen::Vector2d& p) {
    return std::abs(p.x() - 0.5) < 0.15 && std::abs(p.y() - 0.5) < 0.15;
  };
  const Outline o = outline(fill(0, 0, 1, 1, [&](const Eigen::Vector2d& p) { return !hole(p); }));
  ASSERT_EQ(o.rings.size(), 2u);
  EXPECT_EQ(countRings(o, false), 1u);
  EXPECT_EQ(countRings(o, true), 1u);
  const double fillets = (4 - std::numbers::pi) * kAlpha * kAlpha;
  EXPECT_NEAR(o.area_m2, 1.0 - 0.09 + fillets, (4 + 1.2) * kEdgeTolerance);
  for (const Ring& ring : o.rings) {
    if (signedArea(ring) < 0) {
      EXPECT_NEAR(-signedArea(ring), 0.09 - fillets, 1.2 * kEdgeTolerance);
    }
  }
  EXPECT_FALSE(inside(o, {0.5, 0.5}));
  EXPECT_TRUE(inside(o, {0.1, 0.5}));
  expectConsistent(o);
}

// +----------+
// |##########|
// |####  ####|  a 0.06 m hole, narrower than 2 alpha: closed
// |##########|
// +----------+
TEST(Outline, NarrowHoleIsClosed) {
  const Outline o = outline(fill(0, 0, 1, 1, [](const Eigen::Vector2d& p) {
    return std::abs(p.x() - 0.5) > 0.03 || std::abs(p.y() - 0.5) > 0.03;
  }));
  ASSERT_EQ(o.rings.size(), 1u);
  EXPECT_NEAR(o.area_m2, 1.0, 4 * kEdgeTolerance);
  EXPECT_TRUE(inside(o, {0.5, 0.5}));
  expectConsistent(o);
}

// +-----+        +-----+
// |#####|  0.2 m |#####|   gap wider than 2 alpha: two rings
// |#####|<------>|#####|   (a 0.06 m gap is bridged: one ring)
// +-----+        +-----+
TEST(Outline, ClustersFartherThanTwoAlphaStayApart) {
  auto two = [](double gap) {
    std::vector<Eigen::Vector2d> points = fill(0, 0, 0.3, 0.3);
    const std::vector<Eigen::Vector2d> right = fill(0.3 + gap, 0, 0.6 + gap, 0.3);
    points.insert(points.end(), right.begin(), right.end());
    return outline(points);
  };
  const Outline apart = two(0.2);
  ASSERT_EQ(apart.rings.size(), 2u);
  EXPECT_EQ(countRings(apart, false), 2u);
  EXPECT_NEAR(apart.area_m2, 2 * 0.09, 2 * 1.2 * kEdgeTolerance);
  EXPECT_FALSE(inside(apart, {0.4, 0.15}));
  expectConsistent(apart);

  const Outline bridged = two(0.06);
  ASSERT_EQ(bridged.rings.size(), 1u);
  EXPECT_TRUE(inside(bridged, {0.33, 0.15}));
  expectConsistent(bridged);
}

// +----+
// |####|
// |####+----+   the inner corner at (0.5, 0.5) stays concave, up to a fillet of radius alpha:
// |#########|   the missing quadrant is not filled as a convex hull would
// |#########|
// +---------+
TEST(Outline, LShapeKeepsItsConcaveCorner) {
  const Outline o = outline(fill(0, 0, 1, 1, [](const Eigen::Vector2d& p) { return p.x() <= 0.5 || p.y() <= 0.5; }));
  ASSERT_EQ(o.rings.size(), 1u);
  const double fillet = (1 - std::numbers::pi / 4) * kAlpha * kAlpha;
  EXPECT_NEAR(o.area_m2, 0.75 + fillet, 4 * kEdgeTolerance);
  EXPECT_FALSE(inside(o, {0.75, 0.75}));
  EXPECT_FALSE(inside(o, {0.55, 0.55}));  // 0.07 m from the corner, past the fillet
  // The fillet's deepest point lies (sqrt 2 - 1) alpha from the corner, along the diagonal; the
  // raster's disk and the cell-centre boundary each move it by up to a cell.
  const Eigen::Vector2d corner(0.5, 0.5);
  EXPECT_TRUE(inside(o, corner));
  EXPECT_LT(boundaryDistance(o, corner), (std::numbers::sqrt2 - 1) * kAlpha + 2 * kEdgeTolerance);
  expectConsistent(o);
}

// . .  .   . :.  .    scattered points: many small rings, holes, saddles (cells touching at a
//  .: .   .  . ..     corner). The invariants hold whatever the topology.
TEST(Outline, ScatteredPointsKeepTheInvariants) {
  std::size_t holes = 0;
  for (const std::uint64_t seed : {1u, 2u}) {
    Random random(seed);
    std::vector<Eigen::Vector2d> points;
    for (int k = 0; k < 150; ++k) points.emplace_back(0.6 * random.uniform(), 0.3 * random.uniform());
    for (const double alpha : {0.005, 0.015, 0.03}) {
      const Outline o = outline(points, alpha);
      EXPECT_FALSE(o.rings.empty());
      holes += countRings(o, true);
      expectConsistent(o);
      for (const Eigen::Vector2d& p : points) {
        // Every point's cell stays in the region (the closing only adds), so every point is
        // within half a cell diagonal of it.
        EXPECT_TRUE(inside(o, p) || boundaryDistance(o, p) < std::numbers::sqrt2 * kCell)
            << "seed " << seed << " alpha " << alpha << " point " << p.transpose();
      }
    }
  }
  EXPECT_GT(holes, 0u);  // the cases above do cover holes
}

// The closing against a brute-force one on the same cells (indexed from the cell of the lower-left
// point): dilate, then erode, by every cell within alpha. A closed cell's centre lies inside the
// region, an open cell's outside; both at least a third of a cell from the boundary.
TEST(Outline, MatchesBruteForceClosing) {
  Random random(7);
  std::vector<Eigen::Vector2d> points;
  for (int k = 0; k < 80; ++k) points.emplace_back(0.3 * random.uniform(), 0.2 * random.uniform());
  Eigen::Vector2d lo = points[0];
  for (const Eigen::Vector2d& p : points) lo = lo.cwiseMin(p);
  constexpr int kMargin = 8;  // cells around the points' cells, beyond alpha
  constexpr int kSize = 30 + 20 + 2 * kMargin;
  const auto index = [](int i, int j) { return static_cast<std::size_t>((j + kMargin) * kSize + i + kMargin); };
  std::vector<bool> occupied(kSize * kSize, false);
  for (const Eigen::Vector2d& p : points) {
    occupied[index(static_cast<int>(std::floor((p.x() - lo.x()) / kCell)),
                   static_cast<int>(std::floor((p.y() - lo.y()) / kCell)))] = true;
  }
  for (const double alpha : {0.032, 0.045}) {  // 3.2 and 4.5 cells: no lattice distance on the edge
    const double radius2 = (alpha / kCell) * (alpha / kCell);
    const auto within = [&](const std::vector<bool>& set, int i, int j) {
      for (int dj = -5; dj <= 5; ++dj) {
        for (int di = -5; di <= 5; ++di) {
          const int u = i + di, v = j + dj;
          if (di * di + dj * dj > radius2 || u < -kMargin || v < -kMargin || u >= kSize - kMargin ||
              v >= kSize - kMargin) {
            continue;
          }
          if (set[index(u, v)]) return true;
        }
      }
      return false;
    };
    std::vector<bool> dilated(kSize * kSize), open(kSize * kSize);
    for (int j = -kMargin; j < kSize - kMargin; ++j) {
      for (int i = -kMargin; i < kSize - kMargin; ++i) dilated[index(i, j)] = within(occupied, i, j);
    }
    std::vector<bool> outside(kSize * kSize);
    for (std::size_t c = 0; c < dilated.size(); ++c) outside[c] = !dilated[c];
    const Outline o = outline(points, alpha);
    expectConsistent(o);
    for (int j = -kMargin + 5; j < kSize - kMargin - 5; ++j) {  // where the brute force sees all it needs
      for (int i = -kMargin + 5; i < kSize - kMargin - 5; ++i) {
        const bool closed = !within(outside, i, j);
        const Eigen::Vector2d centre = lo + kCell * Eigen::Vector2d(i + 0.5, j + 0.5);
        EXPECT_EQ(inside(o, centre), closed) << "alpha " << alpha << " cell " << i << ", " << j;
        EXPECT_GT(boundaryDistance(o, centre), kCell / 3);
      }
    }
  }
}

TEST(Outline, MaxCellsCapEnlargesTheCell) {
  OutlineOptions options;
  options.alpha_m = kAlpha;
  options.cell_m = 0.001;  // a 1000 x 1000 raster and more
  options.max_cells = 10000;
  const Outline o = outlineOf(fill(0, 0, 1, 1), options);
  EXPECT_GT(o.cell_m, options.cell_m);
  EXPECT_LE(std::size_t{o.raster_width_cells} * o.raster_height_cells, options.max_cells);
  EXPECT_GT(std::size_t{o.raster_width_cells} * o.raster_height_cells, options.max_cells / 2);  // not far too coarse
  ASSERT_EQ(o.rings.size(), 1u);
  EXPECT_NEAR(o.area_m2, 1.0, 4 * 1.5 * o.cell_m);
  expectConsistent(o);
}

TEST(Outline, EmptyInputGivesNothing) {
  const Outline o = outlineOf({});
  EXPECT_TRUE(o.rings.empty());
  EXPECT_TRUE(o.vertices.empty());
  EXPECT_TRUE(o.triangles.empty());
  EXPECT_EQ(o.area_m2, 0.0);
}

//   <>     a lone point: the closing of a cell is the cell, drawn as a diamond through the
//          midpoints to its neighbours' centres, half a cell in area
TEST(Outline, SinglePointGivesATinyRegion) {
  const Eigen::Vector2d p(3.0, -2.0);
  const Outline o = outline({p});
  ASSERT_EQ(o.rings.size(), 1u);
  EXPECT_EQ(o.rings[0].size(), 4u);
  EXPECT_NEAR(o.area_m2, 0.5 * kCell * kCell, kAreaRounding);
  EXPECT_TRUE(inside(o, p) || boundaryDistance(o, p) < kCell);
  for (const Eigen::Vector2d& v : o.rings[0]) EXPECT_LT((v - p).norm(), 1.5 * kCell);
  expectConsistent(o);
}

//   ##         a dense 0.03 m patch, smaller than alpha: the closing adds nothing to it, it does
//   ##         not swell to a disk of radius alpha
TEST(Outline, ClusterSmallerThanAlphaGivesASmallRegion) {
  const Outline o = outline(fill(0, 0, 0.03, 0.03));
  ASSERT_EQ(o.rings.size(), 1u);
  EXPECT_NEAR(o.area_m2, 0.03 * 0.03, 4 * 0.03 * kEdgeTolerance);
  expectConsistent(o);
}

// The same square far from the origin: rasterised from its own corner, so nothing changes.
TEST(Outline, FarFromTheOriginIsTheSame) {
  // Off the cell lines, so that rounding at 5e6 m cannot move the edge points to the next cell.
  const Outline near = outline(fill(0.0013, 0.0017, 0.4987, 0.4983));
  std::vector<Eigen::Vector2d> points = fill(0.0013, 0.0017, 0.4987, 0.4983);
  for (Eigen::Vector2d& p : points) p += Eigen::Vector2d(4.5e5, 5.4e6);
  const Outline far = outline(points);
  EXPECT_NEAR(far.area_m2, near.area_m2, 1e-9);
  EXPECT_EQ(far.rings.size(), near.rings.size());
  EXPECT_EQ(far.triangles.size(), near.triangles.size());
}

}  // namespace
}  // namespace plumb::reco
