#include "ui/viewer/scene_state.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <unordered_map>

#include "cad/measurement.h"
#include "reco/edges_and_corners.h"
#include "ui/viewer/grow_session.h"

namespace plumb::viewer {
namespace {

nlohmann::json vector3(const Eigen::Vector3d& v) {
  return nlohmann::json::array({v.x(), v.y(), v.z()});
}

// What a segment takes from grow `grow`'s snapshot of it: plane, outline and statistics (not its
// name or whether it is still growing).
void takeGrownGeometry(Segment& segment, const reco::SegmentSnapshot& snapshot, std::uint64_t grow) {
  segment.plane = snapshot.plane;
  segment.outline = snapshot.outline;
  segment.points = snapshot.points;
  segment.area_m2 = snapshot.outline ? snapshot.outline->shape.area_m2 : 0.0;
  segment.lambda2 = snapshot.plane.lambda2;
  segment.grow = grow;
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
  std::vector<ecs::Entity> refined;
  for (const reco::SegmentSnapshot& snapshot : update.snapshot.segments) {
    // One surface, one segment: a final result's segment on the surface of one kept already
    // refines it (the newer click's detail) instead of adding a copy.
    if (keep) {
      std::vector<ecs::Entity> taken = refined;  // each kept segment refined once; none of this result's
      taken.insert(taken.end(), segment_entities.begin(), segment_entities.end());
      if (const std::optional<ecs::Entity> held = segmentOnSameSurface(snapshot, update.snapshot, taken)) {
        refineSegment(*held, snapshot, update.grow);
        refined.push_back(*held);
        segment_entities.push_back(*held);
        continue;
      }
    }
    const ecs::Entity entity = registry_.create();
    Segment segment;
    takeGrownGeometry(segment, snapshot, update.grow);
    segment.growing = !keep;
    if (keep) segment.name = "Segment " + std::to_string(++named_.segments);
    registry_.emplace(entity, std::move(segment));
    segment_entities.push_back(entity);
    created.push_back(entity);
  }
  for (const reco::Edge& found : update.snapshot.edges) {
    const std::array<ecs::Entity, 2> segments{segment_entities[found.segments[0]], segment_entities[found.segments[1]]};
    Edge edge{segments, found.start, found.end, found.direction, found.support_points};
    const Eigen::Vector3d snap = 0.5 * (found.start + found.end);
    // Between refined segments the edge may be kept already: it takes the newer support range.
    if (const std::optional<ecs::Entity> kept = keptFeature<Edge>(segments, refined)) {
      registry_.patch<Edge>(*kept, [&](Edge& e) { e = edge; });
      if (registry_.has<SnapCandidate>(*kept)) {
        registry_.patch<SnapCandidate>(*kept, [&](SnapCandidate& c) { c.position = snap; });
      }
      continue;
    }
    const ecs::Entity entity = registry_.create();
    registry_.emplace(entity, std::move(edge));
    registry_.emplace(entity, SnapCandidate{SnapCandidate::Kind::kEdge, snap, entity});
    created.push_back(entity);
  }
  for (const reco::Corner& found : update.snapshot.corners) {
    const std::array<ecs::Entity, 3> segments{segment_entities[found.segments[0]], segment_entities[found.segments[1]],
                                              segment_entities[found.segments[2]]};
    if (const std::optional<ecs::Entity> kept = keptFeature<Corner>(segments, refined)) {
      registry_.patch<Corner>(*kept, [&](Corner& c) {
        c.position = found.position;
        c.support = found.support;
      });
      if (registry_.has<SnapCandidate>(*kept)) {
        registry_.patch<SnapCandidate>(*kept, [&](SnapCandidate& c) { c.position = found.position; });
      }
      continue;
    }
    const ecs::Entity entity = registry_.create();
    registry_.emplace(entity, Corner{segments, found.position, found.support, ""});
    registry_.emplace(entity, SnapCandidate{SnapCandidate::Kind::kCorner, found.position, entity});
    created.push_back(entity);
  }
  if (keep) {
    live_grow_ = 0;
  } else {
    live_ = std::move(created);
  }
}

// The kept Edge or Corner (`Feature`) of the same segments as `segments`, in any order, where
// one of them is `refined` (a feature among new segments only is new). None otherwise.
template <typename Feature, std::size_t N>
std::optional<ecs::Entity> SceneState::keptFeature(const std::array<ecs::Entity, N>& segments,
                                                   const std::vector<ecs::Entity>& refined) const {
  const bool touches_refined = std::any_of(segments.begin(), segments.end(), [&](ecs::Entity s) {
    return std::find(refined.begin(), refined.end(), s) != refined.end();
  });
  if (!touches_refined) return std::nullopt;
  std::array<ecs::Entity, N> wanted = segments;
  std::sort(wanted.begin(), wanted.end());
  std::optional<ecs::Entity> result;
  registry_.view<Feature>().each([&](ecs::Entity entity, const Feature& feature) {
    std::array<ecs::Entity, N> have = feature.segments;
    std::sort(have.begin(), have.end());
    if (!result && have == wanted) result = entity;
  });
  return result;
}

// A kept segment on the surface of `found` (a final result's segment): their planes within 2
// degrees and each one's centroid within the other's reach (t_p, or 3 x the larger RMS), and
// their outlines' extents on the kept plane overlapping or within r of each other. Not one of
// `taken` (refined by another segment of the same result already, or made by it). The first
// such, if any.
std::optional<ecs::Entity> SceneState::segmentOnSameSurface(const reco::SegmentSnapshot& found,
                                                            const reco::GrowSnapshot& grow,
                                                            const std::vector<ecs::Entity>& taken) const {
  if (!found.plane.valid || !found.outline) return std::nullopt;
  constexpr double kMaxAngleDeg = 2.0;
  std::optional<ecs::Entity> result;
  // The extent of an outline's triangulation on the frame of `frame`.
  const auto extent = [](const reco::PlaneOutline& outline, const reco::PlaneOutline& frame) {
    Eigen::AlignedBox2d box;
    for (const Eigen::Vector2d& v : outline.shape.vertices) {
      const Eigen::Vector3d p = outline.toWorld(v) - frame.origin;
      box.extend(Eigen::Vector2d(p.dot(frame.axis_u), p.dot(frame.axis_v)));
    }
    return box;
  };
  registry_.view<Segment>().each([&](ecs::Entity entity, const Segment& segment) {
    if (result || segment.growing || !segment.plane.valid || !segment.outline) return;
    if (std::find(taken.begin(), taken.end(), entity) != taken.end()) return;
    const double cos_angle = std::abs(segment.plane.normal.dot(found.plane.normal));
    if (cos_angle < std::cos(kMaxAngleDeg * M_PI / 180.0)) return;
    const double reach = std::max(grow.plane_threshold_m, 3.0 * std::max(segment.plane.rms, found.plane.rms));
    if (segment.plane.distance(found.plane.centroid) > reach || found.plane.distance(segment.plane.centroid) > reach) {
      return;
    }
    Eigen::AlignedBox2d kept = extent(*segment.outline, *segment.outline);
    const Eigen::AlignedBox2d grown = extent(*found.outline, *segment.outline);
    const Eigen::Vector2d margin = Eigen::Vector2d::Constant(grow.search_radius_m);
    kept = Eigen::AlignedBox2d(kept.min() - margin, kept.max() + margin);
    if (kept.intersects(grown)) result = entity;
  });
  return result;
}

// Gives a kept segment a final result's plane, outline and statistics (its name stays), and
// moves the edges and corners it has onto the new plane: the lines and points where it meets
// the others' planes now (the support range of an edge projected onto its new line). One that
// no longer meets them (planes turned parallel) goes. Inside the result's edit: one undo
// restores it all. The result's own edges and corners of the same segments follow (applyGrow).
void SceneState::refineSegment(ecs::Entity held, const reco::SegmentSnapshot& found, std::uint64_t grow) {
  registry_.patch<Segment>(held, [&](Segment& segment) { takeGrownGeometry(segment, found, grow); });
  const auto planeOf = [&](ecs::Entity segment) { return registry_.get<Segment>(segment).plane; };
  const auto uses = [&](const auto& segments) {
    return std::find(segments.begin(), segments.end(), held) != segments.end();
  };
  std::vector<ecs::Entity> edges, corners, gone;
  registry_.view<Edge>().each([&](ecs::Entity entity, const Edge& edge) {
    if (uses(edge.segments)) edges.push_back(entity);
  });
  registry_.view<Corner>().each([&](ecs::Entity entity, const Corner& corner) {
    if (uses(corner.segments)) corners.push_back(entity);
  });
  for (const ecs::Entity entity : edges) {
    const Edge& edge = registry_.get<Edge>(entity);
    const auto line = reco::lineOfPlanes(planeOf(edge.segments[0]), planeOf(edge.segments[1]));
    if (!line) {
      gone.push_back(entity);
      continue;
    }
    const auto& [origin, direction] = *line;
    const auto onLine = [&](const Eigen::Vector3d& p) { return origin + (p - origin).dot(direction) * direction; };
    const Eigen::Vector3d start = onLine(edge.start), end = onLine(edge.end);
    registry_.patch<Edge>(entity, [&](Edge& e) {
      e.start = start;
      e.end = end;
      e.direction = (end - start).normalized();
    });
    if (registry_.has<SnapCandidate>(entity)) {
      registry_.patch<SnapCandidate>(entity, [&](SnapCandidate& snap) { snap.position = 0.5 * (start + end); });
    }
  }
  for (const ecs::Entity entity : corners) {
    const Corner& corner = registry_.get<Corner>(entity);
    const auto position =
        reco::cornerOfPlanes(planeOf(corner.segments[0]), planeOf(corner.segments[1]), planeOf(corner.segments[2]));
    if (!position) {
      gone.push_back(entity);
      continue;
    }
    registry_.patch<Corner>(entity, [&](Corner& c) { c.position = *position; });
    if (registry_.has<SnapCandidate>(entity)) {
      registry_.patch<SnapCandidate>(entity, [&](SnapCandidate& snap) { snap.position = *position; });
    }
  }
  for (const ecs::Entity entity : gone) registry_.destroy(entity);
}

std::size_t SceneState::deleteSelected() {
  ecs::Registry& registry = registry_;
  std::vector<ecs::Entity> selected;
  registry.view<Selection>().each([&](ecs::Entity entity, const Selection&) { selected.push_back(entity); });
  if (selected.empty()) return 0;
  // A segment takes its edges and corners with it.
  std::vector<ecs::Entity> doomed = selected;
  std::vector<ecs::Entity> doomed_memberships;
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
  // A group takes its membership records with it, not its members.
  registry.view<InGroup>().each([&](ecs::Entity entity, const InGroup& in) {
    if (std::find(selected.begin(), selected.end(), in.group) != selected.end() &&
        std::find(selected.begin(), selected.end(), entity) == selected.end()) {
      doomed_memberships.push_back(entity);
    }
  });
  const auto kind = [&](ecs::Entity e) {
    return registry.has<Segment>(e)       ? "segment"
           : registry.has<Polygon>(e)     ? "polygon"
           : registry.has<Group>(e)       ? "group"
           : registry.has<Measurement>(e) ? "measurement"
                                          : "item";
  };
  ecs::EditScope edit(history_, selected.size() == 1 ? std::string("Delete ") + kind(selected.front())
                                                     : "Delete " + std::to_string(selected.size()) + " items");
  for (const ecs::Entity entity : doomed_memberships) registry.remove<InGroup>(entity);
  for (const ecs::Entity entity : doomed) {
    if (registry.alive(entity)) registry.destroy(entity);
  }
  return selected.size();
}

// --- edits ------------------------------------------------------------------------------------

// Moves `polygon` by `offset`; moved off its plane, it is free.
void SceneState::translate(Polygon& polygon, const Eigen::Vector3d& offset) const {
  for (Eigen::Vector3d& vertex : polygon.vertices) vertex += offset;
  if (const Segment* segment = registry_.tryGet<Segment>(polygon.plane);
      segment && std::abs(segment->plane.normal.dot(offset)) > 1e-9) {
    polygon.plane = ecs::kNullEntity;
  }
}

ecs::Entity SceneState::addPolygon(std::vector<Eigen::Vector3d> ring, ecs::Entity plane) {
  ecs::EditScope edit(history_, "Polygon");
  const ecs::Entity entity = registry_.create();
  registry_.emplace(
      entity, Polygon{std::move(ring), plane, "Polygon " + std::to_string(++named_.polygons), Eigen::Vector3d::Zero()});
  return entity;
}

void SceneState::movePolygon(ecs::Entity polygon, const Eigen::Vector3d& offset) {
  ecs::EditScope edit(history_, "Move polygon");
  registry_.patch<Polygon>(polygon, [&](Polygon& p) { translate(p, offset); });
}

ecs::Entity SceneState::copyPolygon(ecs::Entity polygon, const Eigen::Vector3d& offset) {
  ecs::EditScope edit(history_, "Copy polygon");
  return addCopy(polygon, offset);
}

std::vector<ecs::Entity> SceneState::copyPolygons(ecs::Entity polygon, const std::vector<Eigen::Vector3d>& offsets) {
  ecs::EditScope edit(history_, "Copy polygon " + std::to_string(offsets.size()) + " times");
  std::vector<ecs::Entity> copies;
  for (const Eigen::Vector3d& offset : offsets) copies.push_back(addCopy(polygon, offset));
  return copies;
}

// A copy of `polygon` moved by `offset`, in its group; within an open edit.
ecs::Entity SceneState::addCopy(ecs::Entity polygon, const Eigen::Vector3d& offset) {
  Polygon copy = registry_.get<Polygon>(polygon);
  translate(copy, offset);
  copy.name = "Polygon " + std::to_string(++named_.polygons);
  const ecs::Entity entity = registry_.create();
  registry_.emplace(entity, std::move(copy));
  if (const InGroup* group = registry_.tryGet<InGroup>(polygon)) registry_.emplace(entity, *group);
  return entity;
}

void SceneState::extrudePolygon(ecs::Entity polygon, const Eigen::Vector3d& extrusion) {
  ecs::EditScope edit(history_, "Extrude");
  registry_.patch<Polygon>(polygon, [&](Polygon& p) { p.extrusion = extrusion; });
}

std::variant<ecs::Entity, std::string> SceneState::addCornerOfSelected() {
  std::vector<ecs::Entity> segments;
  for (const ecs::Entity entity : selected()) {
    if (registry_.has<Segment>(entity)) segments.push_back(entity);
  }
  if (segments.size() != 3) {
    return "select three segments (" + std::to_string(segments.size()) + " selected)";
  }
  // The corner keeps its segments in the order they were selected; entity ids are no order to
  // keep (how many live grow snapshots came and went decides them, and that follows the load).
  std::vector<ecs::Entity> wanted = segments;
  std::sort(wanted.begin(), wanted.end());
  bool exists = false;
  registry_.view<Corner>().each([&](ecs::Entity, const Corner& corner) {
    std::array<ecs::Entity, 3> of = corner.segments;
    std::sort(of.begin(), of.end());
    exists = exists || std::equal(of.begin(), of.end(), wanted.begin());
  });
  if (exists) return std::string("these three segments have their corner already");
  const reco::Plane& a = registry_.get<Segment>(segments[0]).plane;
  const reco::Plane& b = registry_.get<Segment>(segments[1]).plane;
  const reco::Plane& c = registry_.get<Segment>(segments[2]).plane;
  const std::optional<Eigen::Vector3d> position = reco::cornerOfPlanes(a, b, c);
  if (!position) return std::string("two of the three planes are nearly parallel, or all three share a line");
  ecs::EditScope edit(history_, "Corner");
  const ecs::Entity entity = registry_.create();
  registry_.emplace(entity, Corner{{segments[0], segments[1], segments[2]},
                                   *position,
                                   {a.lambda2, b.lambda2, c.lambda2},
                                   "Corner " + std::to_string(++named_.corners)});
  registry_.emplace(entity, SnapCandidate{SnapCandidate::Kind::kCorner, *position, entity});
  return entity;
}

ecs::Entity SceneState::addMeasurement(cad::MeasureKind kind, std::vector<cad::MeasureTerm> terms,
                                       std::vector<ecs::Entity> sources) {
  ecs::EditScope edit(history_, "Measure");
  const ecs::Entity entity = registry_.create();
  registry_.emplace(
      entity, Measurement{kind, std::move(terms), std::move(sources),
                          std::string(cad::measureKindTitle(kind)) + " " + std::to_string(++named_.measurements)});
  return entity;
}

void SceneState::rename(ecs::Entity entity, std::string name) {
  ecs::EditScope edit(history_, "Rename");
  if (registry_.has<Segment>(entity)) registry_.patch<Segment>(entity, [&](Segment& s) { s.name = name; });
  if (registry_.has<Polygon>(entity)) registry_.patch<Polygon>(entity, [&](Polygon& p) { p.name = name; });
  if (registry_.has<Corner>(entity)) registry_.patch<Corner>(entity, [&](Corner& c) { c.name = name; });
  if (registry_.has<Measurement>(entity)) {
    registry_.patch<Measurement>(entity, [&](Measurement& m) { m.name = name; });
  }
  if (registry_.has<Group>(entity)) registry_.patch<Group>(entity, [&](Group& g) { g.name = name; });
}

ecs::Entity SceneState::groupSelected() {
  const std::vector<ecs::Entity> items = selected();
  if (items.empty()) return ecs::kNullEntity;
  ecs::EditScope edit(history_, "Group");
  const ecs::Entity group = registry_.create();
  registry_.emplace(group, Group{"Group " + std::to_string(++named_.groups)});
  for (const ecs::Entity item : items) {
    if (!registry_.has<Group>(item)) registry_.emplaceOrReplace(item, InGroup{group});
  }
  return group;
}

void SceneState::ungroupSelected() {
  ecs::EditScope edit(history_, "Ungroup");
  for (const ecs::Entity item : selected()) {
    if (registry_.has<InGroup>(item)) registry_.remove<InGroup>(item);
  }
}

// --- selection ---------------------------------------------------------------------------------

std::vector<ecs::Entity> SceneState::selected() const {
  std::vector<ecs::Entity> entities;
  registry_.view<Selection>().each([&](ecs::Entity entity, const Selection&) { entities.push_back(entity); });
  return entities;
}

void SceneState::select(ecs::Entity entity, bool extend) {
  const bool was_selected = registry_.has<Selection>(entity);
  if (!extend) clearSelection();
  if (was_selected && extend) {
    registry_.remove<Selection>(entity);
  } else {
    registry_.emplaceOrReplace(entity, Selection{});
  }
}

void SceneState::clearSelection() {
  for (const ecs::Entity entity : selected()) registry_.remove<Selection>(entity);
}

void SceneState::clear() {
  dropLive();
  history_.clear();
  std::vector<ecs::Entity> items;
  const auto collect = [&](ecs::Entity entity, const auto&) { items.push_back(entity); };
  registry_.view<Segment>().each(collect);
  registry_.view<Edge>().each(collect);
  registry_.view<Corner>().each(collect);
  registry_.view<Polygon>().each(collect);
  registry_.view<Measurement>().each(collect);
  registry_.view<Group>().each(collect);
  registry_.view<SnapCandidate>().each(collect);
  for (const ecs::Entity entity : items) {
    if (registry_.alive(entity)) registry_.destroy(entity);
  }
  named_ = {};
}

void SceneState::setNameCounters(const NameCounters& counters) {
  named_ = counters;
}

std::string SceneState::toJson() const {
  // Items are numbered in the dump from 1, segments first, then edges, corners, polygons, groups
  // and measurements, each in the scene's order: entity ids would not do, as live grow snapshots consume
  // them in numbers that follow the machine's speed, and a replay must dump the same scene.
  std::unordered_map<ecs::Entity, std::uint64_t> numbers;
  const auto number = [&](ecs::Entity entity) { numbers.emplace(entity, numbers.size() + 1); };
  registry_.view<Segment>().each([&](ecs::Entity entity, const Segment&) { number(entity); });
  registry_.view<Edge>().each([&](ecs::Entity entity, const Edge&) { number(entity); });
  registry_.view<Corner>().each([&](ecs::Entity entity, const Corner&) { number(entity); });
  registry_.view<Polygon>().each([&](ecs::Entity entity, const Polygon&) { number(entity); });
  registry_.view<Group>().each([&](ecs::Entity entity, const Group&) { number(entity); });
  registry_.view<Measurement>().each([&](ecs::Entity entity, const Measurement&) { number(entity); });
  const auto id = [&](ecs::Entity entity) -> nlohmann::json {
    const auto it = numbers.find(entity);
    return it != numbers.end() ? nlohmann::json(it->second) : nlohmann::json(nullptr);
  };
  nlohmann::json segments = nlohmann::json::array();
  registry_.view<Segment>().each([&](ecs::Entity entity, const Segment& segment) {
    segments.push_back({{"id", id(entity)},
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
    edges.push_back({{"id", id(entity)},
                     {"segments", {id(edge.segments[0]), id(edge.segments[1])}},
                     {"start", vector3(edge.start)},
                     {"end", vector3(edge.end)},
                     {"support_points", edge.support_points}});
  });
  nlohmann::json corners = nlohmann::json::array();
  registry_.view<Corner>().each([&](ecs::Entity entity, const Corner& corner) {
    corners.push_back({{"id", id(entity)},
                       {"segments", {id(corner.segments[0]), id(corner.segments[1]), id(corner.segments[2])}},
                       {"name", corner.name},
                       {"position", vector3(corner.position)},
                       {"support", corner.support}});
  });
  const auto group_of = [&](ecs::Entity entity) -> nlohmann::json {
    const InGroup* in = registry_.tryGet<InGroup>(entity);
    return in ? id(in->group) : nlohmann::json(nullptr);
  };
  nlohmann::json polygons = nlohmann::json::array();
  registry_.view<Polygon>().each([&](ecs::Entity entity, const Polygon& polygon) {
    nlohmann::json vertices = nlohmann::json::array();
    for (const Eigen::Vector3d& vertex : polygon.vertices) vertices.push_back(vector3(vertex));
    polygons.push_back({{"id", id(entity)},
                        {"name", polygon.name},
                        {"plane", id(polygon.plane)},
                        {"vertices", vertices},
                        {"extrusion", vector3(polygon.extrusion)},
                        {"group", group_of(entity)}});
  });
  nlohmann::json groups = nlohmann::json::array();
  registry_.view<Group>().each([&](ecs::Entity entity, const Group& group) {
    nlohmann::json members = nlohmann::json::array();
    registry_.view<InGroup>().each([&](ecs::Entity member, const InGroup& in) {
      if (in.group == entity) members.push_back(id(member));
    });
    groups.push_back({{"id", id(entity)}, {"name", group.name}, {"members", members}});
  });
  nlohmann::json measurements = nlohmann::json::array();
  registry_.view<Measurement>().each([&](ecs::Entity entity, const Measurement& measurement) {
    const cad::MeasureValue value = cad::measure(measurement.kind, measurement.terms);
    nlohmann::json terms = nlohmann::json::array(), sources = nlohmann::json::array();
    for (const cad::MeasureTerm& term : measurement.terms) terms.push_back(cad::measureTermKindName(term.kind));
    for (const ecs::Entity source : measurement.sources) sources.push_back(id(source));
    measurements.push_back({{"id", id(entity)},
                            {"name", measurement.name},
                            {"kind", cad::measureKindName(measurement.kind)},
                            {"value", value.value},
                            {"unit", cad::measureUnit(measurement.kind)},
                            {"second", value.second ? nlohmann::json(*value.second) : nlohmann::json(nullptr)},
                            {"text", cad::measureText(measurement.kind, value)},
                            {"from", vector3(value.from)},
                            {"to", vector3(value.to)},
                            {"terms", terms},
                            {"sources", sources},
                            {"group", group_of(entity)}});
  });
  const nlohmann::json scene{{"segments", segments},
                             {"edges", edges},
                             {"corners", corners},
                             {"polygons", polygons},
                             {"groups", groups},
                             {"measurements", measurements},
                             {"undo", history_.canUndo() ? history_.undoName() : std::string_view()}};
  return scene.dump(2) + "\n";
}

}  // namespace plumb::viewer
