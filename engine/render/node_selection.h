#pragma once
// Which octree nodes a frame draws (the level of detail of the renderer): the nodes in the view
// frustum, most important first, under a point budget. Importance is a node's projected size on
// screen; a node is refined (its children considered) while its points lie more than
// max_spacing_px apart on screen. Inner nodes hold a subsample of their children and no point
// is stored twice, so the selection is a tree growing down from the root and the points of all
// selected nodes together are the view's cloud; a node whose children are not loaded yet stands
// in for them with its own subsample.
//
// CPU only, no Vulkan. Thread-safe (reads the immutable octree).

#include <cstdint>
#include <vector>

#include "engine/view/clip_region.h"

namespace plumb::lod {
class Octree;
struct NodeInfo;
}  // namespace plumb::lod
namespace plumb::view {
struct Camera;
}

namespace plumb::render {

struct SelectionOptions {
  std::uint64_t point_budget = 2'000'000;  // the most points a frame draws
  // Refine nodes whose point spacing on screen exceeds this; 0: every node in view, down to the
  // leaves. Below a pixel, since a level's points are not a regular grid: the resolve fills the
  // one-pixel holes that are left.
  double max_spacing_px = 0.6;
};

struct NodeSelection {
  std::vector<const lod::NodeInfo*> nodes;  // most important first; a node's parent comes before it
  std::uint64_t points = 0;                 // in `nodes`, at most the budget
  std::uint64_t culled = 0;                 // nodes considered and found outside the frustum
  bool budget_reached = false;              // a node was left out for the budget
};

// The camera must be valid (view::validateCamera).
// Nodes the clip region cuts away wholly are skipped like those outside the frustum.
NodeSelection selectNodes(const lod::Octree& octree, const view::Camera& camera, const SelectionOptions& options,
                          const view::ClipRegion& clip = {});

}  // namespace plumb::render
