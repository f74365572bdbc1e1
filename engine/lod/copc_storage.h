#pragma once
// A COPC file (io::CopcFile) as an OctreeStorage: opened in place, no import. COPC's VoxelKey
// (d, x, y, z) is Plumb's CellKey over the cube of the info VLR (center +- halfsize), and its
// info spacing is level 0's, halved at each level, as Plumb's root_spacing: the hierarchy becomes
// the node index as it stands, and a node's LAZ chunk is decoded when the node is loaded.

#include <string>

#include "engine/lod/octree_storage.h"

namespace plumb::lod {

// Opens `path` and reads its whole hierarchy (io::CopcFile's checks), then checks that every
// node's parent is in the hierarchy. The header: the points and bounds of the LAS header, the
// cube and spacing of the info VLR, colour for point formats 7 and 8, intensity always, depth
// the deepest level with points, leaf_max_points the most points of a leaf, sampling_grid the
// root cube's size over the spacing. Nodes that hold no points but have descendants stay in the
// index (with 0 points) so that queries descending from the root reach those descendants.
// Throws plumb::Error naming the file and the byte offset.
OpenedOctree openCopcOctree(const std::string& path);

}  // namespace plumb::lod
