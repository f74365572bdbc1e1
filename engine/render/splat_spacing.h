#pragma once
// How much denser the drawn cloud is than a node's own points, per octant of each drawn node:
// the scale of its surfels' radii (surfels.h), which each node measures among its own points.
//
// A node's points are a subsample of its region; where the node is the finest drawn, its
// ancestors' points lie among them, and where a child is drawn, the child's points too. The
// drawn cloud's spacing there is the node's own spacing times sqrt(own points / drawn points).
// The counts come from the octree's sampling: a parent keeps about one point per occupied cell
// of its sampling grid (octree_format.h), so its points in an octant stand for the surface there
// at its density, and its ancestors add about a third as many again (a quarter, a sixteenth, ...).

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
