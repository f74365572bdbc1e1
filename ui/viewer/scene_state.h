#pragma once
// The viewer's scene: the ECS registry and its history, and the one writer of what is in it.
// A grow's snapshots replace its live entities (Segment with growing = true, their Edges,
// Corners and SnapCandidates) at each frame boundary, unrecorded; its final result becomes
// entities in one undoable edit, "Grow". Every other change of the scene (the drawing tools'
// polygons, a corner of three segments, renames, groups, deletions) is one undoable edit too.

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "engine/ecs/history.h"
#include "engine/ecs/registry.h"
#include "ui/viewer/components.h"

namespace plumb::reco {
struct SegmentSnapshot;
struct GrowSnapshot;
}  // namespace plumb::reco

namespace plumb::viewer {

struct GrowUpdate;

class SceneState {
 public:
  SceneState();
  ~SceneState();
  SceneState(const SceneState&) = delete;
  SceneState& operator=(const SceneState&) = delete;

  // Applies a grow's snapshot (GrowSession's update). A final update of a cancelled grow drops
  // its live entities. A final result's segment on the surface of a segment kept already (a
  // second click on a wall) refines that segment instead of adding a copy, in the same edit.
  void applyGrow(const GrowUpdate& update);
  // Drops the live entities of an unfinished grow (a newer click cancelled it).
  void dropLive();
  // Deletes the selected entities, and the edges and corners of selected segments, in one
  // undoable edit. Returns how many selected entities went.
  std::size_t deleteSelected();

  // --- Edits, each one undoable edit named as undoName() shows it ---
  // A polygon (a valid ring: the drawing tools check it) on `plane` (a Segment or null), named
  // "Polygon N". "Polygon".
  ecs::Entity addPolygon(std::vector<Eigen::Vector3d> ring, ecs::Entity plane);
  // "Move polygon": every vertex by `offset`.
  void movePolygon(ecs::Entity polygon, const Eigen::Vector3d& offset);
  // "Copy polygon": a copy moved by `offset`, free of any plane unless the offset lies in it.
  ecs::Entity copyPolygon(ecs::Entity polygon, const Eigen::Vector3d& offset);
  // "Copy polygon N times": copies moved by each of `offsets`, in one edit (an array along a
  // staircase). Returns them in the order of `offsets`.
  std::vector<ecs::Entity> copyPolygons(ecs::Entity polygon, const std::vector<Eigen::Vector3d>& offsets);
  // "Extrude": the polygon becomes a prism (a zero extrusion makes it flat again).
  void extrudePolygon(ecs::Entity polygon, const Eigen::Vector3d& extrusion);
  // "Corner": where the three selected segments meet, even with no points near (a scan
  // shadow), as a Corner and its SnapCandidate; or why there is none (not three segments
  // selected, two of them near parallel, one corner of them exists already).
  std::variant<ecs::Entity, std::string> addCornerOfSelected();
  // "Measure": a measurement of `kind` on `terms` (measureProblem finds nothing: the Measure tool
  // checks), taken on `sources` (one per term, null for none), named "<Kind> N".
  ecs::Entity addMeasurement(cad::MeasureKind kind, std::vector<cad::MeasureTerm> terms,
                             std::vector<ecs::Entity> sources);
  // "Rename": a Segment's, Polygon's, Corner's, Measurement's or Group's name.
  void rename(ecs::Entity entity, std::string name);
  // "Group": a new Group, "Group N", holding the selected items (leaving any group they were in).
  // Null when nothing is selected.
  ecs::Entity groupSelected();
  // "Ungroup": the selected items leave their groups.
  void ungroupSelected();

  // --- Selection (not recorded: it is not part of the document) ---
  std::vector<ecs::Entity> selected() const;
  // Selects `entity` alone, or adds it to (or, when selected, takes it out of) the selection.
  void select(ecs::Entity entity, bool extend);
  void clearSelection();

  // Forgets every item and the history (a project is opened).
  void clear();
  // Continues the "Segment N", "Polygon N", "Corner N", "Group N" and measurements' "<Kind> N"
  // numbering after these counts (a project's items).
  struct NameCounters {
    std::uint64_t segments = 0, polygons = 0, corners = 0, groups = 0, measurements = 0;
  };
  void setNameCounters(const NameCounters& counters);

  ecs::Registry& registry() { return registry_; }
  const ecs::Registry& registry() const { return registry_; }
  ecs::History& history() { return history_; }
  const ecs::History& history() const { return history_; }
  ecs::Entity toolEntity() const { return tool_; }
  const ToolState& tool() const { return registry_.get<ToolState>(tool_); }

  // The scene as JSON (plumb view --dump-scene; docs/user-guide.md): segments, edges, corners,
  // polygons, groups, measurements.
  std::string toJson() const;

 private:
  void destroyAll(std::vector<ecs::Entity>& entities);
  std::optional<ecs::Entity> segmentOnSameSurface(const reco::SegmentSnapshot& found, const reco::GrowSnapshot& grow,
                                                  const std::vector<ecs::Entity>& taken) const;
  void refineSegment(ecs::Entity held, const reco::SegmentSnapshot& found, std::uint64_t grow);
  template <typename Feature, std::size_t N>
  std::optional<ecs::Entity> keptFeature(const std::array<ecs::Entity, N>& segments,
                                         const std::vector<ecs::Entity>& refined) const;
  ecs::Entity addCopy(ecs::Entity polygon, const Eigen::Vector3d& offset);
  void translate(Polygon& polygon, const Eigen::Vector3d& offset) const;

  ecs::Registry registry_;
  ecs::History history_;
  ecs::Entity tool_;
  std::uint64_t live_grow_ = 0;    // the grow the live entities belong to (0: none)
  std::vector<ecs::Entity> live_;  // its segments, edges, corners, snap candidates
  NameCounters named_;             // the N of the last "Segment N", "Polygon N", ... given
};

}  // namespace plumb::viewer
