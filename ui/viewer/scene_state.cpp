#include "ui/viewer/scene_state.h"

#include <algorithm>
#include <nlohmann/json.hpp>

#include "ui/viewer/grow_session.h"

namespace plumb::viewer {
namespace {

nlohmann::json vector3(const Eigen::Vector3d& v) {
  return nlohmann::json::array({v.x(), v.y(), v.z()});
}

}  // namespace

SceneState::SceneState() : history_(registry_), tool_(registry_.create()) {
  registry_.emplace(tool_, ToolState{});
}

SceneState::~SceneState() = default;

void SceneState::destroyAll(std::vector<ecs::Entity>& entities) {
  for (const ecs::Entity entity : entities) {
    if (registry_.alive(entity)) registry_.destroy(entity);
  }
  entities.clear();
}

void SceneState::dropLive() {
  destroyAll(live_);
  live_grow_ = 0;
}

void SceneState::applyGrow(const GrowUpdate& update) {
  destroyAll(live_);
  live_grow_ = update.grow;
  const bool keep = update.final && !update.snapshot.cancelled;
  if (update.final && !keep) {
    live_grow_ = 0;
    return;
  }
  // The final result is one undoable edit; live snapshots are not recorded.
  std::optional<ecs::EditScope> edit;
  if (keep) edit.emplace(history_, "Grow");
  std::vector<ecs::Entity> created;
  std::vector<ecs::Entity> segment_entities;
  for (const reco::SegmentSnapshot& snapshot : update.snapshot.segments) {
    const ecs::Entity entity = registry_.create();
    Segment segment;
    segment.plane = snapshot.plane;
    segment.outline = snapshot.outline;
    segment.points = snapshot.points;
    segment.area_m2 = snapshot.outline ? snapshot.outline->shape.area_m2 : 0.0;
    segment.lambda2 = snapshot.plane.lambda2;
    segment.grow = update.grow;
    segment.growing = !keep;
    if (keep) segment.name = "Segment " + std::to_string(++segments_named_);
    registry_.emplace(entity, std::move(segment));
    segment_entities.push_back(entity);
    created.push_back(entity);
  }
  for (const reco::Edge& found : update.snapshot.edges) {
    const ecs::Entity entity = registry_.create();
    registry_.emplace(entity, Edge{{segment_entities[found.segments[0]], segment_entities[found.segments[1]]},
                                   found.start,
                                   found.end,
                                   found.direction,
                                   found.support_points});
    registry_.emplace(entity, SnapCandidate{SnapCandidate::Kind::kEdge, 0.5 * (found.start + found.end), entity});
    created.push_back(entity);
  }
  for (const reco::Corner& found : update.snapshot.corners) {
    const ecs::Entity entity = registry_.create();
    registry_.emplace(entity, Corner{{segment_entities[found.segments[0]], segment_entities[found.segments[1]],
                                      segment_entities[found.segments[2]]},
                                     found.position,
                                     found.support});
    registry_.emplace(entity, SnapCandidate{SnapCandidate::Kind::kCorner, found.position, entity});
    created.push_back(entity);
  }
  if (keep) {
    live_grow_ = 0;
  } else {
    live_ = std::move(created);
  }
}

std::size_t SceneState::deleteSelected() {
  ecs::Registry& registry = registry_;
  std::vector<ecs::Entity> selected;
  registry.view<Selection>().each([&](ecs::Entity entity, const Selection&) { selected.push_back(entity); });
  if (selected.empty()) return 0;
  // A segment takes its edges and corners with it.
  std::vector<ecs::Entity> doomed = selected;
  const auto uses = [&](const auto& segments) {
    for (const ecs::Entity segment : segments) {
      if (std::find(selected.begin(), selected.end(), segment) != selected.end()) return true;
    }
    return false;
  };
  registry.view<Edge>().each([&](ecs::Entity entity, const Edge& edge) {
    if (uses(edge.segments)) doomed.push_back(entity);
  });
  registry.view<Corner>().each([&](ecs::Entity entity, const Corner& corner) {
    if (uses(corner.segments)) doomed.push_back(entity);
  });
  ecs::EditScope edit(history_, selected.size() == 1 ? "Delete segment" : "Delete segments");
  for (const ecs::Entity entity : doomed) {
    if (registry.alive(entity)) registry.destroy(entity);
  }
  return selected.size();
}

std::string SceneState::toJson() const {
  nlohmann::json segments = nlohmann::json::array();
  registry_.view<Segment>().each([&](ecs::Entity entity, const Segment& segment) {
    segments.push_back({{"id", entity.id()},
                        {"name", segment.name},
                        {"grow", segment.grow},
                        {"growing", segment.growing},
                        {"normal", vector3(segment.plane.normal)},
                        {"offset", segment.plane.offset},
                        {"centroid", vector3(segment.plane.centroid)},
                        {"rms_m", segment.plane.rms},
                        {"points", segment.points},
                        {"area_m2", segment.area_m2},
                        {"lambda2", segment.lambda2},
                        {"outline_rings", segment.outline ? segment.outline->shape.rings.size() : 0}});
  });
  nlohmann::json edges = nlohmann::json::array();
  registry_.view<Edge>().each([&](ecs::Entity entity, const Edge& edge) {
    edges.push_back({{"id", entity.id()},
                     {"segments", {edge.segments[0].id(), edge.segments[1].id()}},
                     {"start", vector3(edge.start)},
                     {"end", vector3(edge.end)},
                     {"support_points", edge.support_points}});
  });
  nlohmann::json corners = nlohmann::json::array();
  registry_.view<Corner>().each([&](ecs::Entity entity, const Corner& corner) {
    corners.push_back({{"id", entity.id()},
                       {"segments", {corner.segments[0].id(), corner.segments[1].id(), corner.segments[2].id()}},
                       {"position", vector3(corner.position)},
                       {"support", corner.support}});
  });
  const ToolState& tool = registry_.get<ToolState>(tool_);
  nlohmann::json measure = nullptr;
  if (tool.measure_done) {
    measure = {{"from", vector3(tool.measure_from)},
               {"to", vector3(tool.measure_to)},
               {"from_kind", snapKindName(tool.measure_from_kind)},
               {"to_kind", snapKindName(tool.measure_to_kind)},
               {"distance_m", (tool.measure_to - tool.measure_from).norm()}};
  }
  const nlohmann::json scene{{"segments", segments}, {"edges", edges}, {"corners", corners}, {"measure", measure}};
  return scene.dump(2) + "\n";
}

}  // namespace plumb::viewer
