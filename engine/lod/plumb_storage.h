#pragma once
// Plumb's own octree file (octree_format.h, docs/octree-format.md) as an OctreeStorage.

#include <string>

#include "engine/lod/octree_storage.h"

namespace plumb::lod {

// Opens and validates `path`: the header's magic, version and checksum, the node index's
// checksum and entries. Throws plumb::Error naming the file and the byte offset for a file that
// is not an octree, is newer than this Plumb, truncated or corrupt. Loads check each node's
// checksum.
OpenedOctree openPlumbOctree(const std::string& path);

}  // namespace plumb::lod
