#pragma once
// The viewer's scene: the ECS registry and its history, and the one writer of the grow results.
// A grow's snapshots replace its live entities (Segment with growing = true, their Edges,
// Corners and SnapCandidates) at each frame boundary, unrecorded; its final result becomes
// entities in one undoable edit, "Grow".

#include <cstdint>
#include <string>
#include <vector>

#include "engine/ecs/history.h"
#include "engine/ecs/registry.h"
#include "ui/viewer/components.h"

namespace plumb::viewer {

struct GrowUpdate;

class SceneState {
 public:
  SceneState();
  ~SceneState();
  SceneState(const SceneState&) = delete;
  SceneState& operator=(const SceneState&) = delete;

  // Applies a grow's snapshot (GrowSession's update). A final update of a cancelled grow drops
  // its live entities.
  void applyGrow(const GrowUpdate& update);
  // Drops the live entities of an unfinished grow (a newer click cancelled it).
  void dropLive();
  // Deletes the selected entities, and the edges and corners of selected segments, in one
  // undoable edit. Returns how many selected entities went.
  std::size_t deleteSelected();

  ecs::Registry& registry() { return registry_; }
  const ecs::Registry& registry() const { return registry_; }
  ecs::History& history() { return history_; }
  ecs::Entity toolEntity() const { return tool_; }
  const ToolState& tool() const { return registry_.get<ToolState>(tool_); }

  // The scene as JSON (plumb view --dump-scene; docs/user-guide.md): segments, edges, corners.
  std::string toJson() const;

 private:
  void destroyAll(std::vector<ecs::Entity>& entities);

  ecs::Registry registry_;
  ecs::History history_;
  ecs::Entity tool_;
  std::uint64_t live_grow_ = 0;       // the grow the live entities belong to (0: none)
  std::vector<ecs::Entity> live_;     // its segments, edges, corners, snap candidates
  std::uint64_t segments_named_ = 0;  // for "Segment N" names
};

}  // namespace plumb::viewer
