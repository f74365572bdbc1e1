#include "engine/render/surfel_estimates.h"

#include <tbb/task_group.h>

#include <algorithm>
#include <array>
#include <new>

#include "engine/lod/node_cache.h"
#include "engine/lod/octree.h"
#include "engine/lod/octree_storage.h"

namespace plumb::render {

struct SurfelEstimates::State {
  std::mutex mutex;
  std::unordered_map<lod::CellKey, std::shared_ptr<const std::vector<Surfel>>, lod::CellKeyHash> ready;
  std::unordered_set<lod::CellKey, lod::CellKeyHash> pending;
  std::size_t outstanding = 0;  // estimates started and not finished
  std::condition_variable done;
  tbb::task_group own;  // runs the estimates without a runner
};

std::vector<Surfel> nodeSurfels(const lod::NodePoints& points, const NodeAncestors& ancestors, double cell_size) {
  // Neighbours farther than an eighth of the node are no surface of it.
  const double reach = cell_size / 8.0;
  std::vector<lod::PackedPoint> around;
  for (const std::shared_ptr<const lod::NodePoints>& ancestor : ancestors) {
    std::array<double, 3> offset;  // from the node's corner to the ancestor's
    for (std::size_t a = 0; a < 3; ++a) offset[a] = ancestor->origin[a] - points.origin[a];
    for (const lod::PackedPoint& q : ancestor->points) {
      const double x = offset[0] + q.x, y = offset[1] + q.y, z = offset[2] + q.z;
      if (std::min({x, y, z}) < -reach || std::max({x, y, z}) > cell_size + reach) continue;
      lod::PackedPoint p = q;
      p.x = static_cast<float>(x);
      p.y = static_cast<float>(y);
      p.z = static_cast<float>(z);
      around.push_back(p);
    }
  }
  return estimateSurfels(points.points, around, cell_size, reach);
}

std::optional<NodeAncestors> nodeAncestors(lod::NodeCache& nodes, const lod::CellKey& key, bool wait) {
  NodeAncestors ancestors;
  bool complete = true;
  for (std::optional<lod::CellKey> above = key.parent(); above; above = above->parent()) {
    const lod::NodeInfo* info = nodes.octree().find(*above);
    if (info == nullptr || info->point_count == 0) continue;
    std::shared_ptr<const lod::NodePoints> points = wait ? nodes.get(*above) : nodes.tryGet(*above);
    if (points) {
      ancestors.push_back(std::move(points));
    } else {
      complete = false;  // the others' loads are started too
    }
  }
  if (!complete) return std::nullopt;
  return ancestors;
}

SurfelEstimates::SurfelEstimates(BackgroundRunner runner)
    : state_(std::make_shared<State>()), runner_(std::move(runner)) {}

SurfelEstimates::~SurfelEstimates() {
  state_->own.wait();
  std::unique_lock lock(state_->mutex);
  state_->done.wait(lock, [&] { return state_->outstanding == 0; });
}

std::shared_ptr<const std::vector<Surfel>> SurfelEstimates::find(const std::shared_ptr<const lod::NodePoints>& points,
                                                                 const NodeAncestors& ancestors, double cell_size) {
  {
    const std::scoped_lock lock(state_->mutex);
    const auto found = state_->ready.find(points->key);
    if (found != state_->ready.end()) return found->second;
    if (!state_->pending.insert(points->key).second) return nullptr;
    ++state_->outstanding;
  }
  auto work = [state = state_, points, ancestors, cell_size] {
    std::shared_ptr<const std::vector<Surfel>> surfels;
    try {
      surfels = std::make_shared<const std::vector<Surfel>>(nodeSurfels(*points, ancestors, cell_size));
    } catch (const std::bad_alloc&) {
      // Out of memory for the estimate: the node's points are drawn as single pixels.
      surfels = std::make_shared<const std::vector<Surfel>>(points->points.size());
    }
    const std::scoped_lock lock(state->mutex);
    state->pending.erase(points->key);
    state->ready.insert_or_assign(points->key, std::move(surfels));
    if (--state->outstanding == 0) state->done.notify_all();
  };
  if (runner_) {
    runner_(std::move(work));
  } else {
    state_->own.run(std::move(work));
  }
  return nullptr;
}

void SurfelEstimates::forget(const lod::CellKey& key) {
  const std::scoped_lock lock(state_->mutex);
  state_->ready.erase(key);
}

}  // namespace plumb::render
