#pragma once
// Which segment each octree point belongs to, for ColourMode::kSegment: per node, one label per
// point of the node, 0 for none (drawn grey). Labels 1, 2, ... get distinct colours.
//
// An immutable value once handed to the renderer (shared, so any thread may have made it); a
// new labelling is a new object with a new version, which the renderer uploads node by node.

#include <cstdint>
#include <unordered_map>
#include <vector>

#include "engine/lod/cell_key.h"

namespace plumb::render {

struct SegmentLabels {
  std::uint64_t version = 0;  // distinct for each labelling
  std::unordered_map<lod::CellKey, std::vector<std::uint32_t>, lod::CellKeyHash> nodes;
};

}  // namespace plumb::render
