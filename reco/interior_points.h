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

std::vector<bool> interiorPoints(const Plane& plane, std::span<const Eigen::Vector3d> points, double step);

// Per point: how many cells of the closed raster its cell lies from the border, by the chessboard
// distance to the nearest empty cell: 1 for the outermost cells, 2 for the ring inside them, and
// so on (a point is interior from 2). 0 only for a degenerate plane or step.
std::vector<std::uint32_t> cellsFromBorder(const Plane& plane, std::span<const Eigen::Vector3d> points, double step);

// Per point: whether it lies within `band_cells` cells of the border (cellsFromBorder) where the
// points of its cell and the eight around it lie to one side of the plane: their mean residual
// more than z standard errors (sigma / sqrt(n)) and more than `min_offset` from 0. The strip of a
// surface that meets the plane there does; a clean cell passes whichever side it leans to, and
// so does a cell a little off a plane that the growth tilted a little.
std::vector<bool> oneSidedBorderPoints(const Plane& plane, std::span<const Eigen::Vector3d> points, double step,
                                       std::uint32_t band_cells, double sigma, double z, double min_offset);

}  // namespace plumb::reco
