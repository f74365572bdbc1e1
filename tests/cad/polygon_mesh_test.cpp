#include "cad/polygon_mesh.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <map>
#include <utility>

namespace plumb::cad {
namespace {

constexpr double kAreaTolerance = 1e-9;    // m^2, sums of a handful of triangles
constexpr double kVolumeTolerance = 1e-6;  // m^3, at UTM coordinates (taken about a nearby point)

using Ring = std::vector<Eigen::Vector3d>;

// `points` (x, y) at height z, moved to `origin`.
Ring ring(std::initializer_list<std::pair<double, double>> points, const Eigen::Vector3d& origin = {0, 0, 0}) {
  Ring result;
  for (const auto& [x, y] : points) result.push_back(origin + Eigen::Vector3d(x, y, 0.0));
  return result;
}

// The area of triangle (a, b, c), positive when it runs counter-clockwise seen from the side
// `normal` points to.
double signedArea(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                  const Eigen::Vector3d& normal) {
  return 0.5 * (b - a).cross(c - a).dot(normal);
}

// Whether p lies inside the ring (a planar ring in z = const), by ray crossing.
bool inside(const Ring& polygon, const Eigen::Vector3d& p) {
  bool in = false;
  for (std::size_t i = 0, j = polygon.size() - 1; i < polygon.size(); j = i++) {
    const Eigen::Vector3d &a = polygon[i], &b = polygon[j];
    if ((a.y() > p.y()) != (b.y() > p.y()) && p.x() < (b.x() - a.x()) * (p.y() - a.y()) / (b.y() - a.y()) + a.x()) {
      in = !in;
    }
  }
  return in;
}

// A triangulation of a ring: n - 2 triangles, each counter-clockwise about the normal, inside the
// ring, together covering its area exactly.
void expectTriangulates(const Ring& polygon, double area, const Eigen::Vector3d& normal) {
  const TriangleMesh mesh = triangulatePolygon(polygon);
  ASSERT_EQ(mesh.positions.size(), polygon.size());
  for (std::size_t i = 0; i < polygon.size(); ++i) EXPECT_EQ(mesh.positions[i], polygon[i]);
  ASSERT_EQ(mesh.triangles.size(), polygon.size() - 2);
  double sum = 0.0;
  for (const auto& [a, b, c] : mesh.triangles) {
    const double triangle = signedArea(mesh.positions[a], mesh.positions[b], mesh.positions[c], normal);
    EXPECT_GT(triangle, 0.0) << "triangle " << a << " " << b << " " << c << " is clockwise or degenerate";
    sum += triangle;
    const Eigen::Vector3d centre = (mesh.positions[a] + mesh.positions[b] + mesh.positions[c]) / 3.0;
    EXPECT_TRUE(inside(polygon, centre)) << "triangle " << a << " " << b << " " << c << " lies outside";
  }
  EXPECT_NEAR(sum, area, kAreaTolerance);
}

// A unit square:
//
//   3 +---+ 2
//     |   |
//   0 +---+ 1
TEST(PolygonMesh, SquareIsTwoCounterClockwiseTriangles) {
  const Ring square = ring({{0, 0}, {1, 0}, {1, 1}, {0, 1}});
  EXPECT_FALSE(findPolygonProblem(square));
  EXPECT_EQ(polygonNormal(square), Eigen::Vector3d::UnitZ());
  expectTriangulates(square, 1.0, Eigen::Vector3d::UnitZ());
}

// An L (concave at vertex 3), 3 m^2:
//
//   5 +---+ 4
//     |   |
//     |   | 3
//     |   +---+ 2
//     |       |
//   0 +-------+ 1
TEST(PolygonMesh, ConcaveLShape) {
  const Ring l = ring({{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}});
  EXPECT_FALSE(findPolygonProblem(l));
  expectTriangulates(l, 3.0, Eigen::Vector3d::UnitZ());
}

// A comb with five teeth, each 0.5 wide and 2 high on a 1 m high back, gaps 0.5 between:
//
//   +-+ +-+ +-+ +-+ +-+
//   | | | | | | | | | |
//   | +-+ +-+ +-+ +-+ |
//   |                 |
//   +-----------------+
TEST(PolygonMesh, CombWithManyReflexVertices) {
  Ring comb = ring({{0, 0}, {4.5, 0}});
  for (int tooth = 4; tooth >= 0; --tooth) {
    const double right = tooth * 1.0 + 0.5, left = tooth * 1.0;
    comb.push_back({right, 3.0, 0.0});
    comb.push_back({left, 3.0, 0.0});
    if (tooth > 0) {
      comb.push_back({left, 1.0, 0.0});
      comb.push_back({left - 0.5, 1.0, 0.0});
    }
  }
  EXPECT_FALSE(findPolygonProblem(comb)) << *findPolygonProblem(comb);
  expectTriangulates(comb, 4.5 * 1.0 + 5 * 0.5 * 2.0, Eigen::Vector3d::UnitZ());
}

// A vertex in the middle of a straight edge, at UTM coordinates, is kept and no triangle is flat.
//
//   4 +-------+ 3
//     |       |
//     |       + 2
//     |       |
//   0 +-------+ 1
TEST(PolygonMesh, StraightVertexAtUtmCoordinates) {
  const Eigen::Vector3d utm(512003.25, 5403007.75, 251.5);
  const Ring square = ring({{0, 0}, {2, 0}, {2, 1}, {2, 2}, {0, 2}}, utm);
  EXPECT_FALSE(findPolygonProblem(square));
  expectTriangulates(square, 4.0, Eigen::Vector3d::UnitZ());
}

// The same square clockwise, and tilted: the normal follows the winding, the triangles the normal.
TEST(PolygonMesh, OrientationFollowsTheWinding) {
  const Ring clockwise = ring({{0, 0}, {0, 1}, {1, 1}, {1, 0}});
  EXPECT_EQ(polygonNormal(clockwise), -Eigen::Vector3d::UnitZ());
  const TriangleMesh mesh = triangulatePolygon(clockwise);
  for (const auto& [a, b, c] : mesh.triangles) {
    EXPECT_LT(signedArea(mesh.positions[a], mesh.positions[b], mesh.positions[c], Eigen::Vector3d::UnitZ()), 0.0);
  }

  const Eigen::AngleAxisd tilt(0.3, Eigen::Vector3d(1, 2, 0).normalized());
  Ring tilted;
  for (const Eigen::Vector3d& p : ring({{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}})) tilted.push_back(tilt * p);
  const Eigen::Vector3d normal = tilt * Eigen::Vector3d::UnitZ();
  EXPECT_LT((polygonNormal(tilted) - normal).norm(), 1e-12);
  EXPECT_FALSE(findPolygonProblem(tilted));
  const TriangleMesh tilted_mesh = triangulatePolygon(tilted);
  double area = 0.0;
  for (const auto& [a, b, c] : tilted_mesh.triangles) {
    const double triangle =
        signedArea(tilted_mesh.positions[a], tilted_mesh.positions[b], tilted_mesh.positions[c], normal);
    EXPECT_GT(triangle, 0.0);
    area += triangle;
  }
  EXPECT_NEAR(area, 3.0, kAreaTolerance);
}

// The volume a closed mesh encloses (divergence theorem), about `reference`: positive when its
// triangles face outward.
double enclosedVolume(const TriangleMesh& mesh, const Eigen::Vector3d& reference) {
  double six_volume = 0.0;
  for (const auto& [a, b, c] : mesh.triangles) {
    const Eigen::Vector3d pa = mesh.positions[a] - reference, pb = mesh.positions[b] - reference,
                          pc = mesh.positions[c] - reference;
    six_volume += pa.dot(pb.cross(pc));
  }
  return six_volume / 6.0;
}

// Closed and consistently oriented: every directed edge once, its reverse once.
void expectClosed(const TriangleMesh& mesh) {
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> directed;
  for (const auto& [a, b, c] : mesh.triangles) {
    ++directed[{a, b}];
    ++directed[{b, c}];
    ++directed[{c, a}];
  }
  for (const auto& [edge, count] : directed) {
    EXPECT_EQ(count, 1) << "edge " << edge.first << "-" << edge.second << " is used " << count << " times";
    EXPECT_EQ(directed.count({edge.second, edge.first}), 1u)
        << "edge " << edge.first << "-" << edge.second << " has no opposite: the mesh is open";
  }
}

// The L above as a prism, 2 m high, at UTM coordinates: up, down, and leaning.
TEST(PolygonMesh, PrismIsClosedWithVolumeAreaTimesHeight) {
  const Eigen::Vector3d utm(512003.25, 5403007.75, 251.5);
  Polygon prism;
  prism.vertices = ring({{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}}, utm);
  for (const Eigen::Vector3d& extrusion :
       {Eigen::Vector3d(0, 0, 2), Eigen::Vector3d(0, 0, -2), Eigen::Vector3d(1, -0.5, 2)}) {
    prism.extrusion = extrusion;
    const TriangleMesh mesh = prismMesh(prism);
    ASSERT_EQ(mesh.positions.size(), 12u);
    EXPECT_EQ(mesh.positions[7], prism.vertices[1] + extrusion);
    // 2 x (6 - 2) caps + 2 x 6 sides.
    EXPECT_EQ(mesh.triangles.size(), 20u);
    expectClosed(mesh);
    EXPECT_NEAR(enclosedVolume(mesh, utm), 3.0 * 2.0, kVolumeTolerance) << extrusion.transpose();
  }
  // Clockwise: the normal points down, the faces still outward.
  std::reverse(prism.vertices.begin(), prism.vertices.end());
  prism.extrusion = {0, 0, 2};
  const TriangleMesh reversed = prismMesh(prism);
  expectClosed(reversed);
  EXPECT_NEAR(enclosedVolume(reversed, utm), 6.0, kVolumeTolerance);
}

TEST(PolygonMesh, PolygonWithoutExtrusionIsItsTriangulation) {
  Polygon flat;
  flat.vertices = ring({{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}});
  const TriangleMesh mesh = prismMesh(flat), triangulated = triangulatePolygon(flat.vertices);
  EXPECT_EQ(mesh.positions, triangulated.positions);
  EXPECT_EQ(mesh.triangles, triangulated.triangles);
}

TEST(PolygonMesh, OutlineMeshIsInWorldCoordinates) {
  reco::PlaneOutline outline;
  outline.origin = {512000.5, 5403000.25, 250.0};
  outline.axis_u = Eigen::Vector3d::UnitY();
  outline.axis_v = Eigen::Vector3d::UnitZ();
  outline.shape.vertices = {{0, 0}, {2, 0}, {0, 1}};
  outline.shape.triangles = {{{0, 1, 2}}};
  const TriangleMesh mesh = outlineMesh(outline);
  ASSERT_EQ(mesh.positions.size(), 3u);
  EXPECT_EQ(mesh.positions[1], Eigen::Vector3d(512000.5, 5403002.25, 250.0));
  EXPECT_EQ(mesh.positions[2], Eigen::Vector3d(512000.5, 5403000.25, 251.0));
  EXPECT_EQ(mesh.triangles, outline.shape.triangles);
  EXPECT_TRUE(outlineMesh(reco::PlaneOutline{}).triangles.empty());
}

void expectProblem(const Ring& polygon, const std::string& part) {
  const std::optional<std::string> problem = findPolygonProblem(polygon);
  ASSERT_TRUE(problem) << "no problem found; expected one saying: " << part;
  EXPECT_NE(problem->find(part), std::string::npos) << *problem << "\nlacks: " << part;
}

// A bow-tie with lobes of different sizes (a symmetric one has no area at all): edge 1-2, from
// (3, 0) to (0, 1), and edge 3-0, from (1, 2) back to (0, 0), cross at (3/7, 6/7).
//
//          3
//   2     /
//   | `. /
//   |   X
//   |  / `.
//   0 /     `. 1
TEST(PolygonMesh, ProblemsNameWhatAndWhere) {
  expectProblem(ring({{0, 0}, {3, 0}, {0, 1}, {1, 2}}),
                "the edge from vertex 1 to vertex 2 meets the edge from vertex 3 to vertex 0");
  expectProblem(ring({{0, 0}, {1, 0}}), "at least 3 vertices, this one has 2");
  expectProblem(ring({{0, 0}, {1, 0}, {2, 0}, {3, 0}}), "no area: its vertices lie on one line");
  Ring bent = ring({{0, 0}, {1, 0}, {1, 1}, {0, 1}});
  bent[2].z() = 0.01;  // 1 cm up: the Newell plane leaves vertex 2 (and 0) about 2.5 mm away
  expectProblem(bent, "off the polygon's plane (the tolerance is 1 mm)");
  EXPECT_FALSE(findPolygonProblem(bent, 0.01)) << "within a 1 cm tolerance";
  Ring nan = ring({{0, 0}, {1, 0}, {1, 1}});
  nan[1].y() = std::nan("");
  expectProblem(nan, "vertex 1 is not finite");
  expectProblem(ring({{0, 0}, {1, 0}, {1, 0}, {1, 1}}), "vertex 2 repeats vertex 1");
  expectProblem(ring({{0, 0}, {1, 0}, {1, 1}, {0, 0}}), "the last vertex (3) repeats the first");
  // Vertex 4 comes down to touch edge 0-1: the ring touches itself.
  //
  //   6 +-+ 5  3 +-+ 2
  //     |  \    /  |
  //     |   \  /   |
  //   0 +----+-----+ 1
  //          4
  expectProblem(ring({{0, 0}, {2, 0}, {2, 2}, {1.5, 2}, {1, 0}, {0.5, 2}, {0, 2}}),
                "the edge from vertex 0 to vertex 1 meets the edge from vertex 3 to vertex 4");
  // From vertex 2 the ring turns straight back down the edge it came up.
  expectProblem(ring({{0, 0}, {2, 0}, {2, 2}, {2, 1}, {0, 1}}), "doubles back on itself at vertex 2");
}

}  // namespace
}  // namespace plumb::cad
