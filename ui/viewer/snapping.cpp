#include "ui/viewer/snapping.h"

#include <Eigen/Geometry>
#include <limits>

#include "engine/ecs/registry.h"
#include "engine/view/camera_controls.h"
#include "ui/viewer/components.h"

namespace plumb::viewer {
namespace {

// A plane whose normal is this close to perpendicular to the ray (about 3 degrees) is seen edge on.
constexpr double kEdgeOnSine = 0.05;

// The point of segment [a, b] nearest to c, as the fraction t along it, clamped to [0, 1].
double nearestFraction(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
  const Eigen::Vector2d ab = b - a;
  const double length2 = ab.squaredNorm();
  return length2 > 0.0 ? std::clamp((c - a).dot(ab) / length2, 0.0, 1.0) : 0.0;
}

bool insideTriangle(const Eigen::Vector2d& p, const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                    const Eigen::Vector2d& c) {
  const auto cross = [](const Eigen::Vector2d& u, const Eigen::Vector2d& v) { return u.x() * v.y() - u.y() * v.x(); };
  const double d1 = cross(b - a, p - a), d2 = cross(c - b, p - b), d3 = cross(a - c, p - c);
  const bool negative = d1 < 0 || d2 < 0 || d3<0, positive = d1> 0 || d2 > 0 || d3 > 0;
  return !(negative && positive);
}

bool insideOutline(const reco::PlaneOutline& outline, const Eigen::Vector3d& world) {
  const Eigen::Vector3d local = world - outline.origin;
  const Eigen::Vector2d p(local.dot(outline.axis_u), local.dot(outline.axis_v));
  const auto& v = outline.shape.vertices;
  for (const auto& t : outline.shape.triangles) {
    if (insideTriangle(p, v[t[0]], v[t[1]], v[t[2]])) return true;
  }
  return false;
}

}  // namespace

const char* snapKindName(Snap::Kind kind) {
  switch (kind) {
    case Snap::Kind::kCorner:
      return "corner";
    case Snap::Kind::kVertex:
      return "vertex";
    case Snap::Kind::kEdge:
      return "edge";
    case Snap::Kind::kPlane:
      return "plane";
    case Snap::Kind::kPoint:
      return "point";
  }
  return "unknown";
}

std::optional<Snap> snapCursor(const ecs::Registry& registry, const view::Camera& camera, double x_px, double y_px,
                               const PointPicker& pick_point, const SnapOptions& options) {
  const Eigen::Vector2d cursor(x_px, y_px);

  // 1. Corners and polygon vertices (a prism's top ones too): the nearest on screen within the radius.
  std::optional<Snap> best;
  const auto consider = [&](Snap::Kind kind, const Eigen::Vector3d& position, ecs::Entity entity) {
    const std::optional<Eigen::Vector2d> pixel = view::pixelOf(camera, position);
    if (!pixel) return;
    const double distance = (*pixel - cursor).norm();
    if (distance <= options.radius_px && (!best || distance < best->distance_px)) {
      best = Snap{kind, position, entity, distance};
    }
  };
  if (options.corners) {
    registry.view<Corner>().each(
        [&](ecs::Entity entity, const Corner& corner) { consider(Snap::Kind::kCorner, corner.position, entity); });
    registry.view<Polygon>().each([&](ecs::Entity entity, const Polygon& polygon) {
      for (const Eigen::Vector3d& vertex : polygon.vertices) {
        consider(Snap::Kind::kVertex, vertex, entity);
        if (!polygon.extrusion.isZero(0.0)) consider(Snap::Kind::kVertex, vertex + polygon.extrusion, entity);
      }
    });
  }
  if (best) return best;

  // 2. Edges within their support range: the point of the edge nearest the cursor's ray.
  const view::Ray ray = view::rayThroughPixel(camera, x_px, y_px);
  registry.view<Edge>().each([&](ecs::Entity entity, const Edge& edge) {
    if (!options.edges) return;
    const std::optional<Eigen::Vector2d> a = view::pixelOf(camera, edge.start), b = view::pixelOf(camera, edge.end);
    if (!a || !b) return;
    const double t = nearestFraction(*a, *b, cursor);
    const double distance = (*a + t * (*b - *a) - cursor).norm();
    if (distance > options.radius_px || (best && distance >= best->distance_px)) return;
    const double length = (edge.end - edge.start).norm();
    const Eigen::Vector3d direction = length > 0.0 ? Eigen::Vector3d((edge.end - edge.start) / length) : edge.direction;
    const double s =
        std::clamp(view::lineParameterNearestRay(edge.start, direction, ray).value_or(t * length), 0.0, length);
    best = Snap{Snap::Kind::kEdge, edge.start + s * direction, entity, distance};
  });
  if (best) return best;

  // 3. A plane seen edge on (a wall in a plan view), as an edge: its outline drawn as a line,
  // within the radius; the point of the outline's edge nearest the cursor's ray, of the nearer
  // edge where edges overlap on screen (a wall's top and bottom seen from above).
  double best_depth = std::numeric_limits<double>::infinity();
  registry.view<Segment>().each([&](ecs::Entity entity, const Segment& segment) {
    if (!options.planes || !options.edge_on_planes || !segment.outline || !segment.plane.valid) return;
    if (std::abs(segment.plane.normal.dot(ray.direction)) > kEdgeOnSine) return;
    const reco::PlaneOutline& outline = *segment.outline;
    for (const auto& ring : outline.shape.rings) {
      for (std::size_t i = 0; i < ring.size(); ++i) {
        const Eigen::Vector2d& next = ring[(i + 1) % ring.size()];
        const Eigen::Vector3d a = outline.origin + ring[i].x() * outline.axis_u + ring[i].y() * outline.axis_v;
        const Eigen::Vector3d b = outline.origin + next.x() * outline.axis_u + next.y() * outline.axis_v;
        const std::optional<Eigen::Vector2d> pa = view::pixelOf(camera, a), pb = view::pixelOf(camera, b);
        const double length = (b - a).norm();
        if (!pa || !pb || length <= 0.0) continue;
        const double t = nearestFraction(*pa, *pb, cursor);
        const double distance = (*pa + t * (*pb - *pa) - cursor).norm();
        if (distance > options.radius_px) continue;
        const Eigen::Vector3d along = (b - a) / length;
        const double s = std::clamp(view::lineParameterNearestRay(a, along, ray).value_or(t * length), 0.0, length);
        const Eigen::Vector3d point = a + s * along;
        const double depth = (point - ray.origin).dot(ray.direction);
        const bool tied = best && std::abs(distance - best->distance_px) < 0.5;
        if (best && !(tied ? depth < best_depth : distance < best->distance_px)) continue;
        best = Snap{Snap::Kind::kPlane, point, entity, distance};
        best_depth = depth;
      }
    }
  });
  if (best) return best;

  // 4. Planes: the nearest hit of the ray on a segment's plane inside its outline.
  double nearest_hit = std::numeric_limits<double>::infinity();
  registry.view<Segment>().each([&](ecs::Entity entity, const Segment& segment) {
    if (!options.planes || !segment.outline || !segment.plane.valid) return;
    const double facing = segment.plane.normal.dot(ray.direction);
    if (std::abs(facing) < 1e-9) return;
    const double t = segment.plane.normal.dot(segment.plane.centroid - ray.origin) / facing;
    if (t <= 0.0 || t >= nearest_hit) return;
    const Eigen::Vector3d hit = ray.origin + t * ray.direction;
    if (!insideOutline(*segment.outline, hit)) return;
    nearest_hit = t;
    best = Snap{Snap::Kind::kPlane, hit, entity, 0.0};
  });
  if (best) return best;

  // 5. A point of the cloud.
  if (pick_point) {
    if (const std::optional<Eigen::Vector3d> point = pick_point(x_px, y_px)) {
      const std::optional<Eigen::Vector2d> pixel = view::pixelOf(camera, *point);
      return Snap{Snap::Kind::kPoint, *point, ecs::kNullEntity, pixel ? (*pixel - cursor).norm() : 0.0};
    }
  }
  return std::nullopt;
}

}  // namespace plumb::viewer
