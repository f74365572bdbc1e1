// Node selection under a point budget, in the manner of Potree (Schuetz 2016, section 3.3):
//   1. Start at the root; keep a queue of candidate nodes ordered by projected size.
//   2. Take the largest. A node outside the frustum, or wholly cut away by the clip region, is
//      dropped with its subtree; a node that
//      would pass the budget ends the selection (what is left is smaller still).
//   3. Otherwise it is selected, and where its points lie further apart on screen than
//      max_spacing_px its children join the queue.

#include "engine/render/node_selection.h"

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <queue>

#include "engine/lod/octree.h"
#include "engine/view/camera.h"

namespace plumb::render {
namespace {

// The six planes of the view frustum (Gribb and Hartmann), as a . (x, 1) >= 0 inside.
std::array<Eigen::Vector4d, 6> frustumPlanes(const view::Camera& camera) {
  const Eigen::Matrix4d clip = view::projectionMatrix(camera) * view::viewMatrix(camera);
  const Eigen::Vector4d w = clip.row(3).transpose();
  std::array<Eigen::Vector4d, 6> planes;
  for (std::size_t axis = 0; axis < 3; ++axis) {
    const Eigen::Vector4d row = clip.row(static_cast<Eigen::Index>(axis)).transpose();
    planes[2 * axis] = w + row;
    planes[2 * axis + 1] = w - row;
  }
  return planes;
}

// Whether the box lies wholly outside one plane: its corner furthest along the normal is out.
bool outside(const std::array<Eigen::Vector4d, 6>& planes, const lod::Box3& box) {
  for (const Eigen::Vector4d& plane : planes) {
    double d = plane[3];
    for (std::size_t a = 0; a < 3; ++a) {
      const double n = plane[static_cast<Eigen::Index>(a)];
      d += n * (n >= 0.0 ? box.max[a] : box.min[a]);
    }
    if (d < 0.0) return true;
  }
  return false;
}

// Pixels per metre at a distance: the scale from world lengths to the screen.
class ScreenScale {
 public:
  explicit ScreenScale(const view::Camera& camera)
      : camera_(camera), pixels_per_metre_(1.0 / view::metresPerPixel(camera, 1.0)) {}
  double pixelsPerMetre(const lod::Box3& box) const {
    if (camera_.projection == view::Projection::kOrthographic) return pixels_per_metre_;
    double squared = 0.0;  // from the eye to the nearest point of the box
    for (std::size_t a = 0; a < 3; ++a) {
      const double eye = camera_.position[static_cast<Eigen::Index>(a)];
      const double d = std::max({box.min[a] - eye, 0.0, eye - box.max[a]});
      squared += d * d;
    }
    return pixels_per_metre_ / std::max(std::sqrt(squared), camera_.near_m);
  }

 private:
  const view::Camera& camera_;
  double pixels_per_metre_;  // at 1 m in front of the eye (orthographic: at any depth)
};

}  // namespace

NodeSelection selectNodes(const lod::Octree& octree, const view::Camera& camera, const SelectionOptions& options,
                          const view::ClipRegion& clip) {
  NodeSelection selection;
  const auto planes = frustumPlanes(camera);
  const ScreenScale scale(camera);
  const view::ClipHalfSpaces clip_spaces = clip.halfSpaces();  // once, for every cell considered
  const lod::Cube& cube = octree.cube();

  struct Candidate {
    const lod::NodeInfo* node;
    double size_px;
    bool operator<(const Candidate& other) const { return size_px < other.size_px; }
  };
  std::priority_queue<Candidate> queue;
  auto consider = [&](const lod::CellKey& key) {
    const lod::NodeInfo* node = octree.find(key);
    if (node == nullptr) return;
    const lod::Box3 box = cube.cellBox(key);
    if (outside(planes, box) ||
        (clip.active() && clip_spaces.cutsAway(Eigen::Vector3d(box.min[0], box.min[1], box.min[2]),
                                               Eigen::Vector3d(box.max[0], box.max[1], box.max[2])))) {
      ++selection.culled;
      return;
    }
    queue.push({node, cube.cellSize(key.level) * scale.pixelsPerMetre(box)});
  };

  consider(lod::CellKey{});
  while (!queue.empty()) {
    const Candidate best = queue.top();
    queue.pop();
    if (selection.points + best.node->point_count > options.point_budget) {
      selection.budget_reached = true;
      break;
    }
    const double spacing_px = octree.spacing(best.node->key.level) * best.size_px / cube.cellSize(best.node->key.level);
    selection.nodes.push_back(best.node);
    selection.points += best.node->point_count;
    if (spacing_px <= options.max_spacing_px) continue;
    for (int octant = 0; octant < 8; ++octant) {
      if (best.node->child_mask & (1u << octant)) consider(best.node->key.child(octant));
    }
  }
  return selection;
}

}  // namespace plumb::render
