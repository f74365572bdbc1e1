#pragma once
// How much denser the drawn cloud is than a node's points and its ancestors', per octant of each
// drawn node: the scale of its surfels' radii (surfels.h), which each node measures among those.
//
// A node's points are a subsample of its region. Where the node is the finest drawn, the drawn
// cloud there is its points and its ancestors': the scale is 1. Where a child is drawn, the
// child's points lie among them, and the drawn cloud's spacing there is the measured one times
// sqrt(measured points / drawn points), the counts from the octree's sampling: a parent keeps
// about one point per occupied cell of its sampling grid (octree_format.h), so its points in an
// octant stand for the surface there at its density, and its ancestors add a quarter as many, a
// sixteenth, ... (a third at most; none for the root).

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "engine/lod/cell_key.h"
#include "engine/lod/octree_format.h"

namespace plumb::render {

struct DrawnNode {
  lod::CellKey key;
  std::uint32_t point_count = 0;
  std::array<std::uint32_t, 8> octant_points{};  // the node's points in each octant (CellKey::child)
};

// Per node of `nodes` (all the nodes a frame draws): the scale of its surfels' radii in each octant.
std::vector<std::array<float, 8>> octantRadiusScales(std::span<const DrawnNode> nodes);

// A node's `points` in each of its octants, the node half_cell wide on each side of its
// centre, split as the splat shader splits them (in float, a coordinate >= half_cell is upper).
std::array<std::uint32_t, 8> countOctants(std::span<const lod::PackedPoint> points, float half_cell);

}  // namespace plumb::render
