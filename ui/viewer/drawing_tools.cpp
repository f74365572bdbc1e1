#include "ui/viewer/drawing_tools.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <limits>
#include <vector>

#include "cad/polygon_mesh.h"
#include "reco/outline.h"
#include "engine/ecs/registry.h"
#include "ui/viewer/components.h"
#include "ui/viewer/direction_finding.h"
#include "ui/viewer/scene_state.h"

namespace plumb::viewer {
namespace {

constexpr double kCloseRadiusPx = 12.0;       // a click this near the first vertex closes the polygon
constexpr double kOnPlaneTolerance_m = 0.01;  // snapped vertices this near a segment's plane lie on it
constexpr double kFreePlanarity_m = 0.01;     // a free polygon's vertices this near their common plane

// The segments a snap lies on: a corner's three, an edge's two, a plane's one, a polygon
// vertex's plane; none for a point of the cloud.
std::vector<ecs::Entity> segmentsOf(const ecs::Registry& registry, const Snap& snap) {
  switch (snap.kind) {
    case Snap::Kind::kCorner:
      if (const Corner* corner = registry.tryGet<Corner>(snap.source)) {
        return {corner->segments.begin(), corner->segments.end()};
      }
      return {};
    case Snap::Kind::kEdge:
      if (const Edge* edge = registry.tryGet<Edge>(snap.source)) return {edge->segments.begin(), edge->segments.end()};
      return {};
    case Snap::Kind::kPlane:
      return {snap.source};
    case Snap::Kind::kVertex:
      if (const Polygon* polygon = registry.tryGet<Polygon>(snap.source);
          polygon && polygon->plane != ecs::kNullEntity) {
        return {polygon->plane};
      }
      return {};
    case Snap::Kind::kPoint:
      return {};
  }
  return {};
}

std::optional<Eigen::Vector3d> rayOnPlane(const view::Ray& ray, const reco::Plane& plane) {
  const double facing = plane.normal.dot(ray.direction);
  if (std::abs(facing) < 1e-9) return std::nullopt;
  const double t = plane.normal.dot(plane.centroid - ray.origin) / facing;
  if (t <= 0.0) return std::nullopt;
  return ray.origin + t * ray.direction;
}

Eigen::Vector3d centroidOf(const std::vector<Eigen::Vector3d>& ring) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& vertex : ring) sum += vertex;
  return sum / static_cast<double>(ring.size());
}

// The rectangle with side a-b whose opposite side passes through c, in `normal`'s plane when
// one is given (zero: the plane of the three points).
std::vector<Eigen::Vector3d> rectangleOf(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                                         const Eigen::Vector3d& normal) {
  const Eigen::Vector3d side = (b - a).normalized();
  Eigen::Vector3d width = (c - b) - (c - b).dot(side) * side;
  if (!normal.isZero(0.0)) width -= width.dot(normal) * normal;
  return {a, b, b + width, a + width};
}

double distanceToScreenSegment(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& p) {
  const Eigen::Vector2d ab = b - a;
  const double t = ab.squaredNorm() > 0.0 ? std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0) : 0.0;
  return (a + t * ab - p).norm();
}

// The segments every feature-snapped vertex lies on; nothing known while none snapped to a feature.
std::optional<std::vector<ecs::Entity>> commonSegments(const DrawingState& d) {
  std::optional<std::vector<ecs::Entity>> common;
  for (const std::optional<std::vector<ecs::Entity>>& on : d.vertex_segments) {
    if (!on) continue;
    if (!common) {
      common = *on;
    } else {
      std::erase_if(*common, [&](ecs::Entity e) { return std::find(on->begin(), on->end(), e) == on->end(); });
    }
  }
  return common;
}

}  // namespace

ecs::Entity polygonAt(const ecs::Registry& registry, const view::Camera& camera, double x_px, double y_px,
                      double radius_px) {
  const Eigen::Vector2d cursor(x_px, y_px);
  ecs::Entity best = ecs::kNullEntity;
  double best_depth = std::numeric_limits<double>::infinity();
  registry.view<Polygon>().each([&](ecs::Entity entity, const Polygon& polygon) {
    // The faces: the ring, and a prism's top and sides.
    std::vector<std::vector<Eigen::Vector3d>> faces{polygon.vertices};
    if (!polygon.extrusion.isZero(0.0)) {
      std::vector<Eigen::Vector3d> top = polygon.vertices;
      for (Eigen::Vector3d& vertex : top) vertex += polygon.extrusion;
      faces.push_back(top);
      for (std::size_t i = 0; i < polygon.vertices.size(); ++i) {
        const Eigen::Vector3d& a = polygon.vertices[i];
        const Eigen::Vector3d& b = polygon.vertices[(i + 1) % polygon.vertices.size()];
        faces.push_back({a, b, b + polygon.extrusion, a + polygon.extrusion});
      }
    }
    for (const std::vector<Eigen::Vector3d>& face : faces) {
      std::vector<Eigen::Vector2d> screen;
      double depth = 0.0;
      for (const Eigen::Vector3d& vertex : face) {
        const std::optional<Eigen::Vector2d> pixel = view::pixelOf(camera, vertex);
        if (!pixel) return;  // partly behind the eye: not pickable from here
        screen.push_back(*pixel);
        depth += (vertex - camera.position).norm();
      }
      depth /= static_cast<double>(face.size());
      bool near = reco::insideRing(screen, cursor);
      for (std::size_t i = 0; i < screen.size() && !near; ++i) {
        near = distanceToScreenSegment(screen[i], screen[(i + 1) % screen.size()], cursor) <= radius_px;
      }
      if (near && depth < best_depth) {
        best_depth = depth;
        best = entity;
      }
    }
  });
  return best;
}

// --- state ---------------------------------------------------------------------------------------

const DrawingState& DrawingTools::state() const {
  return scene_.tool().drawing;
}

template <class F>
void DrawingTools::edit(F&& change) {
  scene_.registry().patch<ToolState>(scene_.toolEntity(), [&](ToolState& tool) { change(tool.drawing); });
}

void DrawingTools::reset() {
  edit([](DrawingState& s) {
    const bool copy = s.copy, rectangle = s.rectangle;
    s = DrawingState{};
    s.copy = copy;
    s.rectangle = rectangle;
  });
}

void DrawingTools::escape() {
  reset();
}

void DrawingTools::lockDirection(bool locked) {
  edit([&](DrawingState& s) {
    s.direction_locked = locked && s.direction.has_value();
    if (locked && !s.direction) s.message = "no direction to lock: point at a plane, an edge or a corner first";
  });
}

// A polygon the tool picked that an undo or a deletion took away: the tool starts over.
void DrawingTools::forgetVanishedPolygon() {
  const DrawingState& s = state();
  if (s.polygon == ecs::kNullEntity || scene_.registry().has<Polygon>(s.polygon)) return;
  edit([](DrawingState& d) {
    d.polygon = ecs::kNullEntity;
    d.base.reset();
    d.copied_from = ecs::kNullEntity;
    d.message = "the polygon is gone (undone or deleted): click a polygon";
  });
}

void DrawingTools::type(char character) {
  const bool accepted = (character >= '0' && character <= '9') || character == '.' || character == '-' ||
                        character == '/' || character == 'x' || character == '*';
  if (!accepted) return;
  edit([&](DrawingState& s) { s.typed.push_back(character); });
}

void DrawingTools::backspace() {
  edit([](DrawingState& s) {
    if (!s.typed.empty()) {
      s.typed.pop_back();
    } else if (!s.vertices.empty()) {
      s.vertices.pop_back();
      s.vertex_segments.pop_back();
    }
  });
}

// --- where the pointer points ----------------------------------------------------------------------

// The point a locked direction runs through: the polygon's last vertex, the move's base, the
// extruded polygon's centroid.
std::optional<Eigen::Vector3d> DrawingTools::constraintOrigin() const {
  const DrawingState& s = state();
  switch (scene_.tool().active) {
    case Tool::kPolygon:
      if (!s.vertices.empty()) return s.vertices.back();
      return std::nullopt;
    case Tool::kMove:
      return s.base;
    case Tool::kExtrude:
      if (const Polygon* polygon = scene_.registry().tryGet<Polygon>(s.polygon)) return centroidOf(polygon->vertices);
      return std::nullopt;
    default:
      return std::nullopt;
  }
}

std::optional<Eigen::Vector3d> DrawingTools::target(const Pointer& pointer) const {
  const DrawingState& s = state();
  const ecs::Registry& registry = scene_.registry();
  const std::optional<Eigen::Vector3d> origin = constraintOrigin();
  if (s.direction_locked && s.direction && origin) {
    return constrainToLine(registry, *origin, s.direction->vector, pointer.snap, pointer.ray);
  }
  // A polygon on a plane: between features the pointer's ray meets that plane.
  const std::optional<std::vector<ecs::Entity>> common = commonSegments(s);
  if (scene_.tool().active == Tool::kPolygon && common && common->size() == 1) {
    const bool feature =
        pointer.snap && pointer.snap->kind != Snap::Kind::kPoint && pointer.snap->kind != Snap::Kind::kPlane;
    if (!feature) {
      if (const Segment* segment = registry.tryGet<Segment>(common->front())) {
        if (std::optional<Eigen::Vector3d> hit = rayOnPlane(pointer.ray, segment->plane)) return hit;
      }
    }
  }
  // Extrusion to a plane: where the line from the centroid along the extrusion meets it.
  if (scene_.tool().active == Tool::kExtrude && origin && pointer.snap && pointer.snap->kind == Snap::Kind::kPlane) {
    if (const std::optional<Eigen::Vector3d> direction = extrusionDirection()) {
      return constrainToLine(registry, *origin, *direction, pointer.snap, pointer.ray);
    }
  }
  if (pointer.snap) return pointer.snap->position;
  return std::nullopt;
}

// The typed distance along the direction from the constraint's origin: the locked direction, or
// the one towards the pointer's target.
std::optional<Eigen::Vector3d> DrawingTools::typedTarget(const Pointer& pointer) const {
  const DrawingState& s = state();
  double distance = 0.0;
  const auto [end, error] = std::from_chars(s.typed.data(), s.typed.data() + s.typed.size(), distance);
  if (error != std::errc() || end != s.typed.data() + s.typed.size() || !std::isfinite(distance)) return std::nullopt;
  const std::optional<Eigen::Vector3d> origin = constraintOrigin();
  if (!origin) return std::nullopt;
  Eigen::Vector3d direction;
  if (s.direction_locked && s.direction) {
    direction = s.direction->vector;
  } else if (scene_.tool().active == Tool::kExtrude && extrusionDirection()) {
    direction = *extrusionDirection();
  } else {
    const std::optional<Eigen::Vector3d> towards = target(pointer);
    if (!towards || (*towards - *origin).norm() < 1e-9) return std::nullopt;
    direction = (*towards - *origin).normalized();
  }
  return *origin + distance * direction;
}

void DrawingTools::updateDirection(const Pointer& pointer, const view::Camera& camera) {
  const DrawingState& s = state();
  if (s.direction_locked) return;
  std::optional<Direction> found;
  // Between the base point and a corner or vertex the direction is from one to the other.
  if (scene_.tool().active == Tool::kMove && s.base && pointer.snap &&
      (pointer.snap->kind == Snap::Kind::kCorner || pointer.snap->kind == Snap::Kind::kVertex) &&
      (pointer.snap->position - *s.base).norm() > 1e-6) {
    found = Direction{(pointer.snap->position - *s.base).normalized(), *s.base, "base to cursor"};
  } else if (pointer.snap) {
    // A pointer at rest keeps the direction its last movement chose at an edge or corner.
    const bool at_rest = pointer.motion_px.norm() < 0.5 && pointer.snap->kind != Snap::Kind::kPlane;
    if (at_rest && s.direction) return;
    found = findDirection(scene_.registry(), camera, *pointer.snap, pointer.motion_px);
  }
  if (!found) return;
  const bool same = s.direction && s.direction->vector.isApprox(found->vector, 1e-12) &&
                    s.direction->anchor.isApprox(found->anchor, 1e-12);
  if (!same) edit([&](DrawingState& d) { d.direction = found; });
}

void DrawingTools::hover(const Pointer& pointer, const view::Camera& camera) {
  forgetVanishedPolygon();
  updateDirection(pointer, camera);
  const std::optional<Eigen::Vector3d> preview = state().typed.empty() ? target(pointer) : typedTarget(pointer);
  std::optional<Eigen::Vector3d> extrusion;
  if (preview && scene_.tool().active == Tool::kExtrude) extrusion = extrusionTo(*preview);
  const auto equal = [](const std::optional<Eigen::Vector3d>& a, const std::optional<Eigen::Vector3d>& b) {
    return a.has_value() == b.has_value() && (!a || *a == *b);
  };
  // Unchanged, the state is left alone: its version decides whether the overlay is rebuilt.
  if (equal(preview, state().preview) && equal(extrusion, state().preview_extrusion)) return;
  edit([&](DrawingState& s) {
    s.preview = preview;
    s.preview_extrusion = extrusion;
  });
}

// --- clicks --------------------------------------------------------------------------------------

void DrawingTools::click(const Pointer& pointer, const view::Camera& camera) {
  forgetVanishedPolygon();
  updateDirection(pointer, camera);
  const Tool tool = scene_.tool().active;
  const DrawingState& s = state();
  if ((tool == Tool::kMove || tool == Tool::kExtrude) && s.polygon == ecs::kNullEntity) {
    pickPolygon(pointer, camera);
    return;
  }
  const std::optional<Eigen::Vector3d> point = target(pointer);
  if (!point) {
    edit([](DrawingState& d) { d.message = "nothing to snap to there"; });
    return;
  }
  switch (tool) {
    case Tool::kPolygon:
      polygonPoint(*point, pointer, camera, false);
      break;
    case Tool::kMove:
      moveTo(*point);
      break;
    case Tool::kExtrude:
      extrudeTo(*point);
      break;
    default:
      break;
  }
}

void DrawingTools::enter(const Pointer& pointer, const view::Camera& camera) {
  forgetVanishedPolygon();
  const Tool tool = scene_.tool().active;
  const std::string& typed = state().typed;
  if (tool == Tool::kMove && !typed.empty() && (typed[0] == '/' || typed[0] == 'x' || typed[0] == '*')) {
    copyArray();
    return;
  }
  if (!state().typed.empty()) {
    const std::optional<Eigen::Vector3d> point = typedTarget(pointer);
    edit([](DrawingState& s) { s.typed.clear(); });
    if (!constraintOrigin()) {
      edit([](DrawingState& s) {
        s.message = "a distance runs from a point: click the first vertex, the base point or the polygon first";
      });
      return;
    }
    if (!point) {
      edit([](DrawingState& s) { s.message = "type a distance in metres (or after a copy /N, xN), then Enter"; });
      return;
    }
    if (tool == Tool::kPolygon) polygonPoint(*point, pointer, camera, true);
    if (tool == Tool::kMove && state().base) moveTo(*point);
    if (tool == Tool::kExtrude && state().polygon != ecs::kNullEntity) extrudeTo(*point);
    return;
  }
  if (tool == Tool::kPolygon) {
    if (state().vertices.size() >= 3) {
      closePolygon();
    } else {
      edit([](DrawingState& s) { s.message = "a polygon needs three vertices before Enter closes it"; });
    }
  }
}

void DrawingTools::pickPolygon(const Pointer& pointer, const view::Camera& camera) {
  const ecs::Entity polygon = polygonAt(scene_.registry(), camera, pointer.pixel.x(), pointer.pixel.y());
  if (polygon == ecs::kNullEntity) {
    edit([](DrawingState& s) { s.message = "click a polygon"; });
    return;
  }
  scene_.select(polygon, false);
  const bool extrude = scene_.tool().active == Tool::kExtrude;
  edit([&](DrawingState& s) {
    s.polygon = polygon;
    s.base.reset();
    s.message = extrude ? "click where its top face goes (a plane, a corner, a point)" : "click the base point";
  });
  updateDirection(pointer, camera);
}

void DrawingTools::polygonPoint(const Eigen::Vector3d& point, const Pointer& pointer, const view::Camera& camera,
                                bool typed) {
  const DrawingState& s = state();
  // Clicking the first vertex closes the polygon (a typed point never does).
  if (!typed && !s.rectangle && s.vertices.size() >= 3) {
    if (const std::optional<Eigen::Vector2d> first = view::pixelOf(camera, s.vertices.front());
        first && (*first - pointer.pixel).norm() <= kCloseRadiusPx) {
      closePolygon();
      return;
    }
  }
  // The segments the vertex lies on: those of the feature it snapped to (a typed point, or one
  // constrained to a locked direction, lies on none that is known).
  std::optional<std::vector<ecs::Entity>> on;
  const bool feature = pointer.snap && pointer.snap->kind != Snap::Kind::kPoint;
  if (feature && !typed && !s.direction_locked) on = segmentsOf(scene_.registry(), *pointer.snap);
  edit([&](DrawingState& d) {
    d.vertices.push_back(point);
    d.vertex_segments.push_back(on);
    d.message = d.rectangle ? (d.vertices.size() == 1 ? "click the other end of the first side"
                                                      : "click a point of the opposite side")
                            : (d.vertices.size() < 3 ? "click the next vertex"
                                                     : "click the next vertex, or the first (or Enter) to close");
  });
  if (state().rectangle && state().vertices.size() == 3) closePolygon();
}

void DrawingTools::closePolygon() {
  const DrawingState& s = state();
  const ecs::Registry& registry = scene_.registry();
  // The plane: the common segment the vertices lie nearest to.
  ecs::Entity plane = ecs::kNullEntity;
  double plane_error = kOnPlaneTolerance_m;
  for (const ecs::Entity segment_entity : commonSegments(s).value_or(std::vector<ecs::Entity>{})) {
    const Segment* segment = registry.tryGet<Segment>(segment_entity);
    if (!segment || !segment->plane.valid) continue;
    double worst = 0.0;
    for (const Eigen::Vector3d& vertex : s.vertices) worst = std::max(worst, segment->plane.distance(vertex));
    if (worst <= plane_error) {
      plane_error = worst;
      plane = segment_entity;
    }
  }
  std::vector<Eigen::Vector3d> ring = s.vertices;
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();
  if (const Segment* segment = registry.tryGet<Segment>(plane)) normal = segment->plane.normal;
  if (s.rectangle && ring.size() == 3) ring = rectangleOf(ring[0], ring[1], ring[2], normal);
  // A ring that is no polygon at all (repeated or collinear points) before any plane is fitted;
  // a failed rectangle takes back its third point, so another can be clicked.
  if (const std::optional<std::string> problem =
          cad::findPolygonProblem(ring, std::numeric_limits<double>::infinity())) {
    edit([&](DrawingState& d) {
      d.message = "not closed: " + *problem;
      if (d.rectangle && !d.vertices.empty()) {
        d.vertices.pop_back();
        d.vertex_segments.pop_back();
      }
    });
    return;
  }
  // Onto the plane: the segment's, or for a free polygon the plane of its vertices.
  Eigen::Vector3d on = plane != ecs::kNullEntity ? registry.get<Segment>(plane).plane.centroid : centroidOf(ring);
  if (plane == ecs::kNullEntity && ring.size() >= 3) {
    normal = cad::polygonNormal(ring);
    double worst = 0.0;
    std::size_t worst_vertex = 0;
    for (std::size_t i = 0; i < ring.size(); ++i) {
      const double distance = std::abs(normal.dot(ring[i] - on));
      if (distance > worst) {
        worst = distance;
        worst_vertex = i;
      }
    }
    if (normal.isZero(0.0) || worst > kFreePlanarity_m) {
      char message[160];
      std::snprintf(message, sizeof message, "not closed: vertex %zu lies %.0f mm off the plane of the others",
                    worst_vertex + 1, worst * 1e3);
      edit([&](DrawingState& d) { d.message = message; });
      return;
    }
  }
  if (!normal.isZero(0.0)) {
    for (Eigen::Vector3d& vertex : ring) vertex -= normal.dot(vertex - on) * normal;
  }
  if (const std::optional<std::string> problem = cad::findPolygonProblem(ring)) {
    edit([&](DrawingState& d) { d.message = "not closed: " + *problem; });
    return;
  }
  const ecs::Entity polygon = scene_.addPolygon(std::move(ring), plane);
  edit([&](DrawingState& d) {
    d.vertices.clear();
    d.vertex_segments.clear();
    d.message = scene_.registry().get<Polygon>(polygon).name + (plane != ecs::kNullEntity ? " on a plane" : " (free)");
  });
}

void DrawingTools::moveTo(const Eigen::Vector3d& point) {
  const DrawingState& s = state();
  if (!s.base) {
    edit([&](DrawingState& d) {
      d.base = point;
      d.message = d.copy ? "click where the copy goes" : "click where it goes";
    });
    return;
  }
  const Eigen::Vector3d offset = point - *s.base;
  if (offset.norm() < 1e-9) {
    edit([](DrawingState& d) { d.message = "that is the base point itself: click where it goes"; });
    return;
  }
  if (s.copy) {
    // The copy becomes the polygon the next click moves on from: a step, then the next.
    const ecs::Entity original = s.polygon;
    const ecs::Entity copy = scene_.copyPolygon(original, offset);
    scene_.select(copy, false);
    edit([&](DrawingState& d) {
      d.copied_from = original;
      d.copied_offset = offset;
      d.polygon = copy;
      d.base = point;
      d.message = "copied; click for another copy, type /N and Enter for N - 1 more between, xN for N in all";
    });
  } else {
    scene_.movePolygon(s.polygon, offset);
    edit([](DrawingState& d) {
      d.base.reset();
      d.polygon = ecs::kNullEntity;
      d.message = "moved";
    });
  }
}

// An extrusion runs along the locked direction, or else along the polygon's normal.
// After a copy: "/N" puts N - 1 more copies evenly between the original and the copy, "xN"
// (or "*N") continues to N copies at the same spacing, as one edit.
void DrawingTools::copyArray() {
  const DrawingState& s = state();
  const std::string text = s.typed.substr(1);
  int n = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), n);
  const bool divide = s.typed[0] == '/';
  if (error != std::errc() || end != text.data() + text.size() || n < 2 || n > 1000 || !s.copy ||
      !scene_.registry().has<Polygon>(s.copied_from)) {
    edit([](DrawingState& d) {
      d.typed.clear();
      d.message = "after a copy, type /N (N from 2 to 1000) or xN, then Enter";
    });
    return;
  }
  std::vector<Eigen::Vector3d> offsets;
  for (int k = divide ? 1 : 2; k < (divide ? n : n + 1); ++k) {
    offsets.push_back(divide ? (static_cast<double>(k) / n) * s.copied_offset
                             : static_cast<double>(k) * s.copied_offset);
  }
  const ecs::Entity original = s.copied_from;
  const Eigen::Vector3d offset = s.copied_offset;
  const std::vector<ecs::Entity> copies = scene_.copyPolygons(original, offsets);
  edit([&](DrawingState& d) {
    d.typed.clear();
    d.message = std::to_string(copies.size()) + (divide ? " copies between" : " more copies");
    if (!divide && !copies.empty() && d.base) {
      // Continued from the last: another xN goes on from there, not over these.
      d.polygon = d.copied_from = copies.back();
      *d.base += static_cast<double>(n - 1) * offset;
    }
  });
}

std::optional<Eigen::Vector3d> DrawingTools::extrusionDirection() const {
  const DrawingState& s = state();
  if (s.direction_locked && s.direction) return s.direction->vector;
  const Polygon* polygon = scene_.registry().tryGet<Polygon>(s.polygon);
  if (!polygon) return std::nullopt;
  return cad::polygonNormal(polygon->vertices);
}

std::optional<Eigen::Vector3d> DrawingTools::extrusionTo(const Eigen::Vector3d& target) const {
  const Polygon* polygon = scene_.registry().tryGet<Polygon>(state().polygon);
  const std::optional<Eigen::Vector3d> direction = extrusionDirection();
  if (!polygon || !direction) return std::nullopt;
  // The top face, parallel to the base, passes through the target.
  const Eigen::Vector3d normal = cad::polygonNormal(polygon->vertices);
  const double along = normal.dot(*direction);
  if (std::abs(along) < 0.1) return std::nullopt;  // the direction lies nearly in the polygon's plane
  const double t = normal.dot(target - polygon->vertices.front()) / along;
  // Thinner than a tenth of a millimetre is no prism (and the project file refuses it).
  if (std::abs(t * along) < 1e-4) return std::nullopt;
  return t * *direction;
}

void DrawingTools::extrudeTo(const Eigen::Vector3d& point) {
  const std::optional<Eigen::Vector3d> extrusion = extrusionTo(point);
  if (!extrusion) {
    edit([](DrawingState& d) {
      d.message = "no extrusion: the target lies in the polygon's plane, or the direction does";
    });
    return;
  }
  scene_.extrudePolygon(state().polygon, *extrusion);
  char message[96];
  std::snprintf(message, sizeof message, "extruded %.4f m", extrusion->norm());
  edit([&](DrawingState& d) {
    d.polygon = ecs::kNullEntity;
    d.message = message;
  });
}

}  // namespace plumb::viewer
