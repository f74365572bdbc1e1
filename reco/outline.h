#pragma once
// The regression polygon (paper section 3.6, "Progress Callback"): the outline of a segment's
// points projected onto its plane, by space carving equivalent to alpha shapes, holes allowed,
// with a triangulation and the area it encloses.
//
// 1. Rasterise the points onto a grid of cells; a cell is occupied when it holds a point.
// 2. Close the occupancy by a disk of radius alpha: dilate, then erode. This carves away every
//    empty disk of radius alpha, which is what the alpha hull is. Both steps threshold the exact
//    Euclidean distance, computed separably as in Felzenszwalb & Huttenlocher (2012, "Distance
//    transforms of sampled functions"), O(cells) for any alpha.
// 3. Trace the boundary of the closed cells by marching squares on the cell centres (iso-value
//    one half, diagonal neighbours connected), dropping collinear vertices.
// 4. Triangulate the same region square by square, one quad per run of full squares in a row.

#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "reco/plane.h"

namespace plumb::reco {

struct OutlineOptions {
  double alpha_m = 0.05;             // gaps narrower than 2*alpha are closed; holes wider stay open
  double cell_m = 0.01;              // raster resolution of the outline
  std::size_t max_cells = 1u << 18;  // raster size cap, bounds time and memory; at least 64
};

// A value type: owns all its data, safe to hand to another thread.
struct Outline {
  std::vector<std::vector<Eigen::Vector2d>> rings;      // outer rings CCW, holes CW; not closed
  std::vector<Eigen::Vector2d> vertices;                // the triangulation of the region
  std::vector<std::array<std::uint32_t, 3>> triangles;  // CCW, indices into vertices
  double area_m2 = 0.0;                                 // of the triangles, = outer rings minus holes
  double cell_m = 0.0;                                  // the resolution actually used
  std::uint32_t raster_width_cells = 0;                 // the raster actually used, padding included
  std::uint32_t raster_height_cells = 0;

  // Whether `p` lies in the region: inside an odd number of rings (holes lie inside their outer ring).
  bool contains(const Eigen::Vector2d& p) const;
};

// Whether `p` lies inside the polygon `ring` (the last vertex joins the first), by the even-odd
// rule; a point on an edge may go either way.
bool insideRing(std::span<const Eigen::Vector2d> ring, const Eigen::Vector2d& p);

// The alpha-shape-like outline of `points` (plane coordinates, metres; the caller projects).
//
// The region is the closing of the occupied cells by a disk of radius `alpha_m`, so a gap or
// hole narrower than 2*alpha is filled and one wider stays open, concave corners keep their
// shape up to a fillet of radius alpha, and clusters farther apart than 2*alpha stay apart.
// Its boundary runs through the centres of the outermost cells, with 45-degree diagonals, so it
// lies within about one cell of the points' true outline; a lone point gives a diamond of half a
// cell's area. Rings never cross and have no repeated or collinear vertices; cells touching only at a
// corner are joined. The triangulation covers exactly the area the rings enclose; it may have
// T-junctions where a merged quad meets smaller triangles.
//
// When the bounding box padded by alpha and two cells would need more than `max_cells` cells,
// the cell grows until it fits, and the outline resolves less: `Outline::cell_m` tells.
//
// Empty `points` give an empty Outline. Points must be finite (asserted). Time and memory are
// O(points + cells), about 14 bytes per cell: under 4 MB and a few milliseconds at 2^18 cells,
// plus a few milliseconds per million points. Reentrant: no shared state.
Outline outlineOf(std::span<const Eigen::Vector2d> points, const OutlineOptions& options = {});

// An outline on a plane in space: plane coordinates (u, v) are origin + u axis_u + v axis_v.
struct PlaneOutline {
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();  // world coordinates
  Eigen::Vector3d axis_u = Eigen::Vector3d::UnitX();
  Eigen::Vector3d axis_v = Eigen::Vector3d::UnitY();
  Outline shape;

  Eigen::Vector3d toWorld(const Eigen::Vector2d& p) const { return origin + p.x() * axis_u + p.y() * axis_v; }
};

// The outline of `points` (world coordinates) projected onto a valid `plane`, in the plane's
// frame: origin at its centroid, axes its tangent and bitangent. O(points) plus outlineOf.
PlaneOutline outlineOnPlane(const Plane& plane, std::span<const Eigen::Vector3d> points,
                            const OutlineOptions& options = {});

}  // namespace plumb::reco
