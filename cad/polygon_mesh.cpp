#include "cad/polygon_mesh.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numeric>

namespace plumb::cad {
namespace {

// The ring in its Newell plane: 2D coordinates relative to its first vertex (so that UTM
// coordinates keep their precision), running counter-clockwise.
struct PlanarRing {
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();  // unit
  std::vector<Eigen::Vector2d> points;
  double extent = 0.0;      // the diagonal of the ring's bounding box, metres
  double orient_eps = 0.0;  // |orient| at or below this counts as collinear
};

// Twice the vector area: the Newell vector, summed as a fan about the first vertex.
Eigen::Vector3d newellVector(std::span<const Eigen::Vector3d> ring) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (std::size_t i = 1; i + 1 < ring.size(); ++i) sum += (ring[i] - ring[0]).cross(ring[i + 1] - ring[0]);
  return sum;
}

double boxDiagonal(std::span<const Eigen::Vector3d> ring) {
  Eigen::Vector3d lo = Eigen::Vector3d::Zero(), hi = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& p : ring) {
    lo = lo.cwiseMin(p - ring[0]);
    hi = hi.cwiseMax(p - ring[0]);
  }
  return (hi - lo).norm();
}

PlanarRing planarRing(std::span<const Eigen::Vector3d> ring, const Eigen::Vector3d& normal) {
  PlanarRing planar;
  planar.normal = normal;
  // (u, v, normal) is right-handed, so a ring counter-clockwise about the normal is
  // counter-clockwise in (u, v).
  const Eigen::Vector3d u = normal.unitOrthogonal();
  const Eigen::Vector3d v = normal.cross(u);
  planar.points.reserve(ring.size());
  for (const Eigen::Vector3d& p : ring) planar.points.emplace_back((p - ring[0]).dot(u), (p - ring[0]).dot(v));
  planar.extent = boxDiagonal(ring);
  planar.orient_eps = 1e-12 * planar.extent * planar.extent;
  return planar;
}

// Twice the signed area of (a, b, c): positive when they turn counter-clockwise.
double orient(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
  const Eigen::Vector2d ab = b - a, ac = c - a;
  return ab.x() * ac.y() - ab.y() * ac.x();
}

int side(double orientation, double eps) {
  return orientation > eps ? 1 : (orientation < -eps ? -1 : 0);
}

// Whether p, collinear with a and b, lies on the segment between them.
bool onSegment(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& p) {
  const Eigen::Vector2d ab = b - a;
  const double t = (p - a).dot(ab) / ab.squaredNorm();
  constexpr double kSlack = 1e-12;
  return t >= -kSlack && t <= 1.0 + kSlack;
}

// Whether the closed segments ab and cd have a point in common.
bool segmentsMeet(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c,
                  const Eigen::Vector2d& d, double eps) {
  const int o1 = side(orient(a, b, c), eps), o2 = side(orient(a, b, d), eps);
  const int o3 = side(orient(c, d, a), eps), o4 = side(orient(c, d, b), eps);
  if (o1 * o2 < 0 && o3 * o4 < 0) return true;
  return (o1 == 0 && onSegment(a, b, c)) || (o2 == 0 && onSegment(a, b, d)) || (o3 == 0 && onSegment(c, d, a)) ||
         (o4 == 0 && onSegment(c, d, b));
}

std::string millimetres(double metres) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g mm", metres * 1000.0);
  return text;
}

std::optional<std::string> findSelfContact(const PlanarRing& planar) {
  const std::vector<Eigen::Vector2d>& q = planar.points;
  const std::size_t n = q.size();
  // Consecutive edges meet at their shared vertex only, unless the ring turns back there.
  for (std::size_t k = 0; k < n; ++k) {
    const Eigen::Vector2d& prev = q[(k + n - 1) % n];
    const Eigen::Vector2d& next = q[(k + 1) % n];
    if (side(orient(prev, q[k], next), planar.orient_eps) == 0 && (prev - q[k]).dot(next - q[k]) > 0.0) {
      return "the ring doubles back on itself at vertex " + std::to_string(k);
    }
  }
  for (std::size_t i = 0; i < n; ++i) {
    // Edges i and j are consecutive when j = i + 1, or when i is the first edge and j the last.
    for (std::size_t j = i + 2; j < n; ++j) {
      if (i == 0 && j == n - 1) continue;
      if (segmentsMeet(q[i], q[i + 1], q[j], q[(j + 1) % n], planar.orient_eps)) {
        return "the edge from vertex " + std::to_string(i) + " to vertex " + std::to_string(i + 1) +
               " meets the edge from vertex " + std::to_string(j) + " to vertex " + std::to_string((j + 1) % n) +
               ": the ring is not simple (it crosses or touches itself)";
      }
    }
  }
  return std::nullopt;
}

// Whether p lies in the closed triangle (a, b, c), which is counter-clockwise.
bool inClosedTriangle(const Eigen::Vector2d& p, const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                      const Eigen::Vector2d& c, double eps) {
  return orient(a, b, p) >= -eps && orient(b, c, p) >= -eps && orient(c, a, p) >= -eps;
}

}  // namespace

std::optional<std::string> findPolygonProblem(std::span<const Eigen::Vector3d> ring, double planarity_tolerance_m) {
  const std::size_t n = ring.size();
  if (n < 3) return "a polygon needs at least 3 vertices, this one has " + std::to_string(n);
  for (std::size_t i = 0; i < n; ++i) {
    if (!ring[i].allFinite()) return "vertex " + std::to_string(i) + " is not finite (NaN or infinite coordinates)";
  }
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t next = (i + 1) % n;
    if ((ring[next] - ring[i]).norm() > kPolygonResolution) continue;
    if (next == 0) {
      return "the last vertex (" + std::to_string(i) +
             ") repeats the first: a ring is closed without repeating its first vertex";
    }
    return "vertex " + std::to_string(next) + " repeats vertex " + std::to_string(i) +
           " (closer than 1 micrometre); drop one of them";
  }
  const Eigen::Vector3d newell = newellVector(ring);
  const double area = 0.5 * newell.norm();
  if (!(area > kPolygonResolution * boxDiagonal(ring))) {
    return std::string("the polygon has no area: its vertices lie on one line");
  }
  const Eigen::Vector3d normal = newell.normalized();

  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();  // relative to the first vertex
  for (const Eigen::Vector3d& p : ring) centroid += p - ring[0];
  centroid /= static_cast<double>(n);
  std::size_t worst = 0;
  double worst_distance = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const double distance = std::abs(normal.dot(ring[i] - ring[0] - centroid));
    if (distance > worst_distance) {
      worst = i;
      worst_distance = distance;
    }
  }
  if (worst_distance > planarity_tolerance_m) {
    return "vertex " + std::to_string(worst) + " is " + millimetres(worst_distance) +
           " off the polygon's plane (the tolerance is " + millimetres(planarity_tolerance_m) + ")";
  }
  return findSelfContact(planarRing(ring, normal));
}

Eigen::Vector3d polygonNormal(std::span<const Eigen::Vector3d> ring) {
  assert(ring.size() >= 3 && "polygonNormal needs a ring of at least 3 vertices");
  const Eigen::Vector3d newell = newellVector(ring);
  assert(newell.norm() > 0.0 && "polygonNormal of a ring without area: check it with findPolygonProblem");
  return newell.normalized();
}

TriangleMesh triangulatePolygon(std::span<const Eigen::Vector3d> ring) {
  assert(!findPolygonProblem(ring, std::numeric_limits<double>::infinity()) &&
         "triangulatePolygon needs a simple ring with an area: check it with findPolygonProblem first");
  const PlanarRing planar = planarRing(ring, polygonNormal(ring));
  const std::vector<Eigen::Vector2d>& q = planar.points;
  const double eps = planar.orient_eps;

  TriangleMesh mesh;
  mesh.positions.assign(ring.begin(), ring.end());
  mesh.triangles.reserve(ring.size() - 2);
  // The ring still to triangulate, as indices; it stays simple and counter-clockwise as ears go.
  std::vector<std::uint32_t> left(ring.size());
  std::iota(left.begin(), left.end(), 0u);
  while (left.size() > 3) {
    const std::size_t m = left.size();
    const auto corner = [&](std::size_t k) {
      return std::array<std::uint32_t, 3>{left[(k + m - 1) % m], left[k], left[(k + 1) % m]};
    };
    std::size_t ear = m;
    std::size_t most_convex = 0;
    double most_convex_turn = -std::numeric_limits<double>::infinity();
    for (std::size_t k = 0; k < m && ear == m; ++k) {
      const auto [a, b, c] = corner(k);
      const double turn = orient(q[a], q[b], q[c]);
      if (turn > most_convex_turn) {
        most_convex = k;
        most_convex_turn = turn;
      }
      // A reflex or straight corner is no ear.
      if (turn <= eps) continue;
      // Nor is one whose triangle holds another vertex, even on its border: the new diagonal
      // would pass through it.
      bool empty = true;
      for (const std::uint32_t j : left) {
        if (j != a && j != b && j != c && inClosedTriangle(q[j], q[a], q[b], q[c], eps)) {
          empty = false;
          break;
        }
      }
      if (empty) ear = k;
    }
    // A simple ring always has an ear; should rounding hide every one, clip the most convex corner
    // rather than stall.
    if (ear == m) ear = most_convex;
    mesh.triangles.push_back(corner(ear));
    left.erase(left.begin() + static_cast<std::ptrdiff_t>(ear));
  }
  mesh.triangles.push_back({left[0], left[1], left[2]});
  return mesh;
}

TriangleMesh prismMesh(const Polygon& polygon) {
  TriangleMesh flat = triangulatePolygon(polygon.vertices);
  if (!polygon.isPrism()) return flat;
  const Eigen::Vector3d normal = polygonNormal(polygon.vertices);
  const double rise = normal.dot(polygon.extrusion);
  assert(rise != 0.0 && "prismMesh of an extrusion within the polygon's plane: check it with findProjectProblem");
  // The ring runs counter-clockwise about the normal, so its own triangles face the normal's side:
  // outward for the face the extrusion moves away from that side, inward for the other.
  const bool along_normal = rise > 0.0;
  const auto n = static_cast<std::uint32_t>(polygon.vertices.size());

  TriangleMesh mesh;
  mesh.positions = flat.positions;
  for (const Eigen::Vector3d& p : polygon.vertices) mesh.positions.push_back(p + polygon.extrusion);
  mesh.triangles.reserve(2 * flat.triangles.size() + 2 * n);
  for (const auto& [a, b, c] : flat.triangles) {
    if (along_normal) {
      mesh.triangles.push_back({a, c, b});
      mesh.triangles.push_back({a + n, b + n, c + n});
    } else {
      mesh.triangles.push_back({a, b, c});
      mesh.triangles.push_back({a + n, c + n, b + n});
    }
  }
  // Side i runs from vertex i to the next, then up; (i, j, j', i') faces outward when the
  // extrusion is along the normal (edge x extrusion points away from the ring's inside).
  for (std::uint32_t i = 0; i < n; ++i) {
    const std::uint32_t j = (i + 1) % n;
    if (along_normal) {
      mesh.triangles.push_back({i, j, j + n});
      mesh.triangles.push_back({i, j + n, i + n});
    } else {
      mesh.triangles.push_back({i, i + n, j + n});
      mesh.triangles.push_back({i, j + n, j});
    }
  }
  return mesh;
}

TriangleMesh outlineMesh(const reco::PlaneOutline& outline) {
  TriangleMesh mesh;
  mesh.positions.reserve(outline.shape.vertices.size());
  for (const Eigen::Vector2d& v : outline.shape.vertices) mesh.positions.push_back(outline.toWorld(v));
  mesh.triangles = outline.shape.triangles;
  for ([[maybe_unused]] const auto& triangle : mesh.triangles) {
    assert(std::max({triangle[0], triangle[1], triangle[2]}) < mesh.positions.size() &&
           "outline triangle beyond its vertices: check the outline with findProjectProblem");
  }
  return mesh;
}

}  // namespace plumb::cad
