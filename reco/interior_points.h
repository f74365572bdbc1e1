#pragma once
// Which points of a planar point set lie away from its border: the robust final fit
// (region_grower.cpp, refine) weighs those by least squares and the others, where the strips of
// the surfaces that meet the plane lie, by the biweight.
//
// A raster of `step` on the plane holds the points' projections; a closing (a dilation, then an
// erosion, by one cell) fills the cells that missed a point by chance; a point is interior where
// the closed raster holds its cell and the eight around it. With step at least twice the points'
// spacing, a cell misses a point by chance about once in fifty (e^-4), and the closing fills
// almost all of those. The border is the outermost cells, along the outline and the holes: a band
// up to a step wide. (Two cells wide, the band made the room evaluation worse: full detail 1.03
// to 1.15 times the limit at 1 mm noise, the biweight costing more than the strips it kept out.)
// The raster is coarsened (step doubled) until it has at most kMaxInteriorCells cells.

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "reco/plane.h"

namespace plumb::reco {

inline constexpr std::size_t kMaxInteriorCells = std::size_t{1} << 24;

// The closed raster of a planar point set: for each of its cells the chessboard distance to the
// nearest empty cell (1 for the outermost cells, 2 for the ring inside them, and so on; 0 for an
// empty cell), and each point's cell. Empty for a degenerate plane or step, where every point
// lies 0 cells from the border.
struct BorderRaster {
  std::size_t width = 0;                   // cells across; rows follow each other
  std::vector<std::uint32_t> from_border;  // per cell
  std::vector<std::size_t> cell_of;        // per point
  std::uint32_t cellsFromBorder(std::size_t point) const { return cell_of.empty() ? 0 : from_border[cell_of[point]]; }
  bool interior(std::size_t point) const { return cellsFromBorder(point) >= 2; }
};
BorderRaster borderRaster(const Plane& plane, std::span<const Eigen::Vector3d> points, double step);

// Per point: BorderRaster::interior.
std::vector<bool> interiorPoints(const Plane& plane, std::span<const Eigen::Vector3d> points, double step);

// Per point of `points` (those `raster` was drawn from, on `plane`): whether it lies within
// `band_cells` cells of the border where the points of its cell and the eight around it lie to
// one side of the plane: their mean residual more than z standard errors (sigma / sqrt(n)) and
// more than `min_offset` from 0. The strip of a surface that meets the plane there does; a clean
// cell passes whichever side it leans to, and so does a cell a little off a plane that the growth
// tilted a little.
std::vector<bool> oneSidedBorderPoints(const BorderRaster& raster, const Plane& plane,
                                       std::span<const Eigen::Vector3d> points, std::uint32_t band_cells,
                                       double sigma, double z, double min_offset);

}  // namespace plumb::reco
