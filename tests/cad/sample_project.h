#pragma once
// A small project at UTM coordinates that every cad test shares: a room's corner.
//
//            z
//            |  wall x (segment 11)
//            |_______
//           /|       |         y
//          / |   +---+ window (polygon 40, on wall y)
//         /  |   +---+        /
//        /   +--------------- /-- wall y (segment 12) lies in x-z
//       /   / O = corner 30  /
//      /   /    floor (segment 10, a hole in the middle),
//     /   /     an L (polygon 41) and a box (prism 42) on it
//    x
//
// Groups 1 ("walls") and 2 ("furniture"); edges 20, 21, 22 along the three intersections; the
// corner 30 where all three meet; measurements 50 to 55, one of each kind. Coordinates are deliberately untidy doubles
// (a slightly tilted floor, an origin with nine decimals) so that a round trip that loses a bit shows.

#include <Eigen/Geometry>
#include <vector>

#include "cad/project.h"
#include "reco/outline.h"

namespace plumb::cad::test {

inline const Eigen::Vector3d kOrigin{512000.123456789, 5403000.987654321, 250.0625};

// A plane through `centroid` with unit `normal`, its tangent near `towards`.
inline reco::Plane samplePlane(const Eigen::Vector3d& centroid, const Eigen::Vector3d& normal,
                               const Eigen::Vector3d& towards) {
  reco::Plane plane;
  plane.valid = true;
  plane.normal = normal.normalized();
  plane.tangent = (towards - towards.dot(plane.normal) * plane.normal).normalized();
  plane.bitangent = plane.normal.cross(plane.tangent);
  plane.centroid = centroid;
  plane.offset = -plane.normal.dot(centroid);
  plane.lambda0 = 1.0 / 3.0;
  plane.lambda1 = 0.1 / 7.0;
  plane.lambda2 = 4.1e-6;
  plane.point_count = 123457;
  plane.rms = 0.0020248;
  return plane;
}

// A segment whose outline is the rectangle [-half_u, half_u] x [-half_v, half_v] about the centroid.
inline Segment rectangleSegment(ItemId id, const char* name, const reco::Plane& plane, double half_u, double half_v) {
  Segment segment{id, name, 1, plane, {}};
  segment.outline.origin = plane.centroid;
  segment.outline.axis_u = plane.tangent;
  segment.outline.axis_v = plane.bitangent;
  reco::Outline& shape = segment.outline.shape;
  shape.rings = {{{-half_u, -half_v}, {half_u, -half_v}, {half_u, half_v}, {-half_u, half_v}}};
  shape.vertices = shape.rings[0];
  shape.triangles = {{{0, 1, 2}}, {{0, 2, 3}}};
  shape.area_m2 = 4.0 * half_u * half_v;
  shape.cell_m = 0.01;
  shape.raster_width_cells = 7;
  shape.raster_height_cells = 5;
  return segment;
}

inline Project sampleProject() {
  const Eigen::Vector3d o = kOrigin;
  Project project;
  project.cloud_path = "scans/room é.plumb";
  view::Camera camera;
  camera.position = o + Eigen::Vector3d(5.25, -4.125, 1.7);
  camera.target = o + Eigen::Vector3d(1.0, 1.0, 1.0);
  camera.fov_deg = 47.5;
  camera.viewport_width_px = 1600;
  camera.viewport_height_px = 900;
  project.camera = camera;
  project.groups = {{1, "walls"}, {2, "furniture"}};

  // The floor: an outline grown from points on a grid, with a square hole.
  const reco::Plane floor_plane =
      samplePlane(o + Eigen::Vector3d(2.0, 1.5, 0.0), Eigen::Vector3d(1e-4, -2e-4, 1.0), Eigen::Vector3d::UnitX());
  std::vector<Eigen::Vector3d> floor_points;
  for (int i = 0; i <= 80; ++i) {
    for (int j = 0; j <= 60; ++j) {
      const double u = -2.0 + 0.05 * i, v = -1.5 + 0.05 * j;
      if (std::abs(u) < 0.5 && std::abs(v) < 0.5) continue;
      floor_points.push_back(floor_plane.centroid + u * floor_plane.tangent + v * floor_plane.bitangent);
    }
  }
  reco::OutlineOptions options;
  options.alpha_m = 0.1;
  options.cell_m = 0.05;
  Segment floor{10, "floor", 1, floor_plane, reco::outlineOnPlane(floor_plane, floor_points, options)};
  project.segments.push_back(std::move(floor));
  project.segments.push_back(rectangleSegment(
      11, "wall x",
      samplePlane(o + Eigen::Vector3d(0.0, 1.5, 1.25), Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY()), 1.5, 1.25));
  project.segments.push_back(rectangleSegment(
      12, "", samplePlane(o + Eigen::Vector3d(2.0, 0.0, 1.25), -Eigen::Vector3d::UnitY(), Eigen::Vector3d::UnitX()),
      2.0, 1.25));

  project.edges = {{20, "floor | wall x", 1, {10, 11}, o, o + Eigen::Vector3d(0.0, 3.0, 0.0)},
                   {21, "", 1, {10, 12}, o, o + Eigen::Vector3d(4.0, 0.0, 0.0)},
                   {22, "", 0, {11, 12}, o, o + Eigen::Vector3d(0.0, 0.0, 2.5)}};
  project.corners = {
      {30, "corner \"A\", north", 1, {10, 11, 12}, o + Eigen::Vector3d(1e-4, -2e-4, 3e-4), {4.1e-6, 5.3e-6, 6.7e-7}},
      {31, "", 0, {10, 11, 0}, o + Eigen::Vector3d(0.5, 0.25, 0.125), {1e-6, 2e-6, 0.0}}};

  // A window on wall y (the plane y = o.y), an L on the floor (concave), a box on the floor.
  project.polygons.push_back(
      {40, "window 1", 1, 12,
       std::vector<Eigen::Vector3d>{o + Eigen::Vector3d(1.0, 0.0, 1.0), o + Eigen::Vector3d(2.0, 0.0, 1.0),
                                    o + Eigen::Vector3d(2.0, 0.0, 2.0), o + Eigen::Vector3d(1.0, 0.0, 2.0)},
       Eigen::Vector3d::Zero()});
  project.polygons.push_back(
      {41, "L", 0, 0,
       std::vector<Eigen::Vector3d>{o + Eigen::Vector3d(2.5, 0.5, 0.0), o + Eigen::Vector3d(3.5, 0.5, 0.0),
                                    o + Eigen::Vector3d(3.5, 1.0, 0.0), o + Eigen::Vector3d(3.0, 1.0, 0.0),
                                    o + Eigen::Vector3d(3.0, 2.0, 0.0), o + Eigen::Vector3d(2.5, 2.0, 0.0)},
       Eigen::Vector3d::Zero()});
  project.polygons.push_back(
      {42, "", 2, 10,
       std::vector<Eigen::Vector3d>{o + Eigen::Vector3d(0.5, 2.0, 0.0), o + Eigen::Vector3d(1.5, 2.0, 0.0),
                                    o + Eigen::Vector3d(1.5, 2.75, 0.0), o + Eigen::Vector3d(0.5, 2.75, 0.0)},
       Eigen::Vector3d(0.0, 0.0, 0.8125)});

  // One measurement of each kind, on the items above and on points of the cloud (source 0).
  const auto point = [](const Eigen::Vector3d& p) {
    return MeasureTerm{MeasureTerm::Kind::kPoint, p, Eigen::Vector3d::Zero(), {}};
  };
  const auto plane = [](const Eigen::Vector3d& p, const Eigen::Vector3d& normal) {
    return MeasureTerm{MeasureTerm::Kind::kPlane, p, normal.normalized(), {}};
  };
  const MeasureTerm wall_x = plane(o + Eigen::Vector3d(0.0, 1.0, 1.0), Eigen::Vector3d::UnitX());
  const MeasureTerm on_floor = plane(o + Eigen::Vector3d(1.0, 1.0, 0.0), floor_plane.normal);
  project.measurements = {
      {50,
       "corner to desk",
       2,
       MeasureKind::kDistance,
       {point(project.corners[0].position), point(o + Eigen::Vector3d(3.25, 2.125, 0.75))},
       {30, 0}},
      {51,
       "wall to floor edge",
       1,
       MeasureKind::kAngle,
       {wall_x,
        MeasureTerm{MeasureTerm::Kind::kLine, o + Eigen::Vector3d(2.0, 0.0, 0.0), Eigen::Vector3d::UnitX(), {}}},
       {11, 21}},
      {52, "", 0, MeasureKind::kPointToPlane, {wall_x, point(o + Eigen::Vector3d(3.9375, 2.0, 1.0))}, {11, 0}},
      {53,
       "room width",
       0,
       MeasureKind::kBetweenPlanes,
       {wall_x, plane(o + Eigen::Vector3d(4.0, 2.0, 1.5), Eigen::Vector3d(-1.0, 1e-3, 0.0))},
       {11, 0}},
      {54, "ceiling height", 0, MeasureKind::kHeight, {on_floor, point(o + Eigen::Vector3d(1.5, 1.5, 2.5))}, {10, 0}},
      {55,
       "L area",
       2,
       MeasureKind::kArea,
       {MeasureTerm{MeasureTerm::Kind::kPolygon, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(),
                    project.polygons[1].vertices}},
       {41}}};
  return project;
}

}  // namespace plumb::cad::test
