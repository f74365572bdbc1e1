#include "ui/viewer/project_bridge.h"

#include <charconv>
#include <unordered_map>

#include "cad/measurement.h"
#include "engine/ecs/registry.h"
#include "ui/viewer/components.h"
#include "ui/viewer/scene_state.h"

namespace plumb::viewer {
namespace {

// N of a name "<prefix>N", or 0.
std::uint64_t numberAfter(const std::string& name, std::string_view prefix) {
  if (name.size() <= prefix.size() || name.compare(0, prefix.size(), prefix) != 0) return 0;
  std::uint64_t n = 0;
  const auto [end, error] = std::from_chars(name.data() + prefix.size(), name.data() + name.size(), n);
  return error == std::errc() && end == name.data() + name.size() ? n : 0;
}

}  // namespace

std::uint64_t documentVersion(const ecs::Registry& registry) {
  return registry.version<Segment>() + registry.version<Edge>() + registry.version<Corner>() +
         registry.version<Polygon>() + registry.version<Measurement>() + registry.version<Group>() +
         registry.version<InGroup>();
}

cad::Project projectOf(const ecs::Registry& registry, std::string cloud_path, std::optional<view::Camera> camera) {
  cad::Project project;
  project.cloud_path = std::move(cloud_path);
  project.camera = std::move(camera);
  std::unordered_map<std::uint64_t, cad::ItemId> ids;  // entity id -> item id
  cad::ItemId next = 1;
  const auto idOf = [&](ecs::Entity entity) -> cad::ItemId {
    const auto it = ids.find(entity.id());
    return entity != ecs::kNullEntity && it != ids.end() ? it->second : cad::kNoItem;
  };
  const auto groupOf = [&](ecs::Entity entity) {
    const InGroup* in = registry.tryGet<InGroup>(entity);
    return in ? idOf(in->group) : cad::kNoItem;
  };
  registry.view<Group>().each([&](ecs::Entity entity, const Group& group) {
    ids[entity.id()] = next;
    project.groups.push_back({next++, group.name});
  });
  registry.view<Segment>().each([&](ecs::Entity entity, const Segment& segment) {
    if (segment.growing || !segment.plane.valid) return;
    ids[entity.id()] = next;
    cad::Segment out;
    out.id = next++;
    out.name = segment.name;
    out.group = groupOf(entity);  // groups have their ids already
    out.plane = segment.plane;
    if (segment.outline) out.outline = *segment.outline;
    project.segments.push_back(std::move(out));
  });
  registry.view<Edge>().each([&](ecs::Entity entity, const Edge& edge) {
    const cad::ItemId a = idOf(edge.segments[0]), b = idOf(edge.segments[1]);
    if (a == cad::kNoItem || b == cad::kNoItem) return;  // of a live grow
    ids[entity.id()] = next;
    project.edges.push_back({next++, "", groupOf(entity), {a, b}, edge.start, edge.end});
  });
  registry.view<Corner>().each([&](ecs::Entity entity, const Corner& corner) {
    const std::array<cad::ItemId, 3> of{idOf(corner.segments[0]), idOf(corner.segments[1]), idOf(corner.segments[2])};
    if (of[0] == cad::kNoItem || of[1] == cad::kNoItem || of[2] == cad::kNoItem) return;
    ids[entity.id()] = next;
    project.corners.push_back({next++, corner.name, groupOf(entity), of, corner.position, corner.support});
  });
  registry.view<Polygon>().each([&](ecs::Entity entity, const Polygon& polygon) {
    ids[entity.id()] = next;
    project.polygons.push_back(
        {next++, polygon.name, groupOf(entity), idOf(polygon.plane), polygon.vertices, polygon.extrusion});
  });
  // Last: a measurement names the items it was taken on (those since deleted are none).
  registry.view<Measurement>().each([&](ecs::Entity entity, const Measurement& measurement) {
    std::vector<cad::ItemId> sources;
    for (const ecs::Entity source : measurement.sources) sources.push_back(idOf(source));
    ids[entity.id()] = next;
    project.measurements.push_back(
        {next++, measurement.name, groupOf(entity), measurement.kind, measurement.terms, std::move(sources)});
  });
  return project;
}

void loadProject(const cad::Project& project, SceneState& scene) {
  scene.clear();
  ecs::Registry& registry = scene.registry();
  std::unordered_map<cad::ItemId, ecs::Entity> entities;
  const auto entityOf = [&](cad::ItemId id) {
    const auto it = entities.find(id);
    return it == entities.end() ? ecs::kNullEntity : it->second;
  };
  SceneState::NameCounters named;
  for (const cad::Group& group : project.groups) {
    const ecs::Entity entity = registry.create();
    registry.emplace(entity, Group{group.name});
    entities[group.id] = entity;
    named.groups = std::max(named.groups, numberAfter(group.name, "Group "));
  }
  const auto join = [&](ecs::Entity entity, cad::ItemId group) {
    if (const ecs::Entity g = entityOf(group); g != ecs::kNullEntity) registry.emplace(entity, InGroup{g});
  };
  for (const cad::Segment& in : project.segments) {
    const ecs::Entity entity = registry.create();
    Segment segment;
    segment.plane = in.plane;
    segment.plane.valid = true;
    if (!in.outline.shape.rings.empty()) segment.outline = std::make_shared<const reco::PlaneOutline>(in.outline);
    segment.points = in.plane.point_count;
    segment.area_m2 = in.outline.shape.area_m2;
    segment.lambda2 = in.plane.lambda2;
    segment.name = in.name;
    registry.emplace(entity, std::move(segment));
    join(entity, in.group);
    entities[in.id] = entity;
    named.segments = std::max(named.segments, numberAfter(in.name, "Segment "));
  }
  for (const cad::Edge& in : project.edges) {
    const ecs::Entity entity = registry.create();
    const Eigen::Vector3d along = in.end - in.start;
    const Eigen::Vector3d direction =
        along.norm() > 0.0 ? Eigen::Vector3d(along.normalized()) : Eigen::Vector3d::UnitX();
    registry.emplace(entity,
                     Edge{{entityOf(in.segments[0]), entityOf(in.segments[1])}, in.start, in.end, direction, 0});
    registry.emplace(entity, SnapCandidate{SnapCandidate::Kind::kEdge, 0.5 * (in.start + in.end), entity});
    join(entity, in.group);
    entities[in.id] = entity;
  }
  for (const cad::Corner& in : project.corners) {
    const ecs::Entity entity = registry.create();
    registry.emplace(entity, Corner{{entityOf(in.segments[0]), entityOf(in.segments[1]), entityOf(in.segments[2])},
                                    in.position,
                                    in.support,
                                    in.name});
    registry.emplace(entity, SnapCandidate{SnapCandidate::Kind::kCorner, in.position, entity});
    join(entity, in.group);
    entities[in.id] = entity;
    named.corners = std::max(named.corners, numberAfter(in.name, "Corner "));
  }
  for (const cad::Polygon& in : project.polygons) {
    const ecs::Entity entity = registry.create();
    registry.emplace(entity, Polygon{in.vertices, entityOf(in.plane), in.name, in.extrusion});
    join(entity, in.group);
    entities[in.id] = entity;
    named.polygons = std::max(named.polygons, numberAfter(in.name, "Polygon "));
  }
  for (const cad::Measurement& in : project.measurements) {
    const ecs::Entity entity = registry.create();
    std::vector<ecs::Entity> sources;
    for (const cad::ItemId source : in.sources) sources.push_back(entityOf(source));
    registry.emplace(entity, Measurement{in.kind, in.terms, std::move(sources), in.name});
    join(entity, in.group);
    entities[in.id] = entity;
    named.measurements =
        std::max(named.measurements, numberAfter(in.name, std::string(cad::measureKindTitle(in.kind)) + " "));
  }
  scene.setNameCounters(named);
}

}  // namespace plumb::viewer
