#pragma once
// The surfels of the nodes a streaming frame uploads, estimated off the frame (surfels.h: a few
// milliseconds a node of 20,000 points, too long to hold a frame for): a frame asks for a node's,
// starts their estimate the first time and uploads the node once they are ready.

#include <condition_variable>
#include <cstddef>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include "engine/lod/cell_key.h"
#include "engine/render/surfels.h"

namespace plumb::lod {
class NodeCache;
struct NodePoints;
}  // namespace plumb::lod

namespace plumb::render {

// A node's ancestors' points, all of them drawn wherever the node is: its surfels' neighbours too.
using NodeAncestors = std::vector<std::shared_ptr<const lod::NodePoints>>;

// The points of the ancestors of node `key` that have any, parent first, from `nodes`: loaded
// where they are not (`wait`), else their loads started and nothing returned while one is
// missing.
std::optional<NodeAncestors> nodeAncestors(lod::NodeCache& nodes, const lod::CellKey& key, bool wait);

class SurfelEstimates {
 public:
  // Runs a piece of work in the background (the viewer's job system); empty: a task group of
  // the estimates' own.
  using BackgroundRunner = std::function<void(std::function<void()> work)>;

  explicit SurfelEstimates(BackgroundRunner runner);
  // Waits for the estimates under way.
  ~SurfelEstimates();
  SurfelEstimates(const SurfelEstimates&) = delete;
  SurfelEstimates& operator=(const SurfelEstimates&) = delete;

  // The surfels of `points` (a node `cell_size` wide, with those `ancestors`) once estimated;
  // else null, their estimate started unless it is under way.
  std::shared_ptr<const std::vector<Surfel>> find(const std::shared_ptr<const lod::NodePoints>& points,
                                                  const NodeAncestors& ancestors, double cell_size);
  // Forgets a node's surfels (uploaded with its points).
  void forget(const lod::CellKey& key);

 private:
  struct State;
  std::shared_ptr<State> state_;  // shared with the estimates under way
  BackgroundRunner runner_;
};

// The surfels of a node `cell_size` wide with those ancestors, as the renderer estimates them.
std::vector<Surfel> nodeSurfels(const lod::NodePoints& points, const NodeAncestors& ancestors, double cell_size);

}  // namespace plumb::render
