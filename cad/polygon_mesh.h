#pragma once
// Triangle meshes of a project's items: the rules a drawn polygon must follow, its Newell normal,
// its triangulation by ear clipping, the closed mesh of a prism, and the mesh of a segment's
// outline. World coordinates, metres, double precision throughout.
//
// Every function is pure and reentrant; none keeps state between calls.

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "cad/project.h"
#include "reco/outline.h"

namespace plumb::cad {

struct TriangleMesh {
  std::vector<Eigen::Vector3d> positions;
  std::vector<std::array<std::uint32_t, 3>> triangles;  // indices into positions
};

// Two vertices closer than this are the same vertex, and a polygon narrower than this (area over
// its bounding box's diagonal) has no area: far below what a scan resolves, far above the rounding
// of UTM coordinates (about 1e-9 m).
inline constexpr double kPolygonResolution = 1e-6;  // metres

// What makes `ring` (a closed ring: the last vertex joins the first and is not repeated) unusable as
// a polygon, as a sentence naming the vertex (0-based), or nothing when it is a valid polygon. The
// rules, checked in this order: at least 3 vertices; every coordinate finite; no vertex within
// kPolygonResolution of the next one (the last one's next is the first); an area; every vertex
// within `planarity_tolerance_m` of the plane through the vertices' centroid perpendicular to the
// Newell normal; no two edges meeting except consecutive ones at their shared vertex (a ring that
// crosses itself, touches itself or doubles back is not simple). Vertices on a straight line
// through the middle of an edge are allowed. O(n^2) in the vertex count.
std::optional<std::string> findPolygonProblem(std::span<const Eigen::Vector3d> ring,
                                              double planarity_tolerance_m = 1e-3);

// The unit Newell normal of `ring`: the direction from which the ring runs counter-clockwise.
// The ring needs at least 3 vertices and an area (asserted).
Eigen::Vector3d polygonNormal(std::span<const Eigen::Vector3d> ring);

// The triangulation of a simple ring, convex or concave, by ear clipping in its Newell plane:
// positions are the ring's vertices (same order, same values), n - 2 triangles, each
// counter-clockwise seen from the side polygonNormal points to. The ring must pass
// findPolygonProblem, planarity aside (asserted); a ring off its plane gives triangles through its
// vertices. O(n^3) in the worst case, meant for drawn polygons (tens of vertices).
TriangleMesh triangulatePolygon(std::span<const Eigen::Vector3d> ring);

// The closed surface of a prism: positions are the ring's n vertices, then the same moved by the
// extrusion; the base and the top are triangulatePolygon's triangles, the sides two triangles per
// ring edge; every triangle counter-clockwise seen from outside, every edge shared by exactly two
// triangles. A polygon without extrusion gives its triangulatePolygon mesh. The ring must be
// valid (asserted) and the extrusion must leave its plane (findProjectProblem checks both).
TriangleMesh prismMesh(const Polygon& polygon);

// The outline's triangulation in world coordinates: one position per outline vertex (toWorld), its
// triangles unchanged (counter-clockwise seen from axis_u x axis_v). Empty for an empty outline.
// The triangles' indices must lie below the vertex count (asserted).
TriangleMesh outlineMesh(const reco::PlaneOutline& outline);

}  // namespace plumb::cad
