#include "ui/viewer/direction_finding.h"

#include <Eigen/Geometry>
#include <cmath>
#include <limits>
#include <vector>

#include "cad/polygon_mesh.h"
#include "engine/ecs/registry.h"

namespace plumb::viewer {
namespace {

// Of `candidates` (unit vectors at `anchor`), the one whose image on screen the movement follows
// most closely, signed along the movement.
std::optional<Eigen::Vector3d> followedCandidate(const view::Camera& camera, const Eigen::Vector3d& anchor,
                                                 const std::vector<Eigen::Vector3d>& candidates,
                                                 const Eigen::Vector2d& motion_px) {
  const std::optional<Eigen::Vector2d> at = view::pixelOf(camera, anchor);
  if (!at) return std::nullopt;
  // A step small against the distance to the eye, so the image is the direction's tangent on screen.
  const double step = std::max(1e-3, 0.01 * (anchor - camera.position).norm());
  const bool moved = motion_px.norm() >= 0.5;
  std::optional<Eigen::Vector3d> best;
  double best_score = -1.0;
  for (const Eigen::Vector3d& candidate : candidates) {
    const std::optional<Eigen::Vector2d> tip = view::pixelOf(camera, anchor + step * candidate);
    if (!tip) continue;
    const Eigen::Vector2d image = *tip - *at;
    const double length = image.norm();
    if (length < 1e-9) continue;
    const double score = moved ? std::abs(image.dot(motion_px)) / (length * motion_px.norm()) : length;
    if (score > best_score) {
      best_score = score;
      best = moved && image.dot(motion_px) < 0.0 ? Eigen::Vector3d(-candidate) : candidate;
    }
  }
  return best;
}

}  // namespace

std::optional<Direction> findDirection(const ecs::Registry& registry, const view::Camera& camera, const Snap& snap,
                                       const Eigen::Vector2d& motion_px) {
  std::vector<Eigen::Vector3d> candidates;
  const char* source = "";
  switch (snap.kind) {
    case Snap::Kind::kPlane: {
      const Segment* segment = registry.tryGet<Segment>(snap.source);
      if (!segment || !segment->plane.valid) return std::nullopt;
      Eigen::Vector3d normal = segment->plane.normal;
      if (normal.dot(camera.position - snap.position) < 0.0) normal = -normal;
      return Direction{normal.normalized(), snap.position, "plane normal"};
    }
    case Snap::Kind::kEdge: {
      const Edge* edge = registry.tryGet<Edge>(snap.source);
      if (!edge) return std::nullopt;
      candidates.push_back(edge->direction.normalized());
      source = "edge";
      break;
    }
    case Snap::Kind::kCorner: {
      const Corner* corner = registry.tryGet<Corner>(snap.source);
      if (!corner) return std::nullopt;
      for (int i = 0; i < 3; ++i) {
        const Segment* a = registry.tryGet<Segment>(corner->segments[static_cast<std::size_t>(i)]);
        const Segment* b = registry.tryGet<Segment>(corner->segments[static_cast<std::size_t>((i + 1) % 3)]);
        if (!a || !b) continue;
        const Eigen::Vector3d line = a->plane.normal.cross(b->plane.normal);
        if (line.norm() > 1e-6) candidates.push_back(line.normalized());
      }
      source = "corner edge";
      break;
    }
    case Snap::Kind::kVertex: {
      const Polygon* polygon = registry.tryGet<Polygon>(snap.source);
      if (!polygon || polygon->vertices.size() < 3) return std::nullopt;
      const std::vector<Eigen::Vector3d>& ring = polygon->vertices;
      // The vertex snapped: of the base ring, or of a prism's top (the base moved by the extrusion).
      std::size_t nearest = 0;
      double nearest_distance = std::numeric_limits<double>::infinity();
      for (std::size_t i = 0; i < ring.size(); ++i) {
        for (const Eigen::Vector3d& position : {ring[i], Eigen::Vector3d(ring[i] + polygon->extrusion)}) {
          const double distance = (position - snap.position).squaredNorm();
          if (distance < nearest_distance) {
            nearest_distance = distance;
            nearest = i;
          }
        }
      }
      for (const std::size_t other : {(nearest + 1) % ring.size(), (nearest + ring.size() - 1) % ring.size()}) {
        const Eigen::Vector3d side = ring[other] - ring[nearest];
        if (side.norm() > 1e-9) candidates.push_back(side.normalized());
      }
      candidates.push_back(cad::polygonNormal(ring));  // a drawn polygon's ring is valid
      if (!polygon->extrusion.isZero(0.0)) candidates.push_back(polygon->extrusion.normalized());
      source = "polygon side";
      break;
    }
    case Snap::Kind::kPoint:
      return std::nullopt;
  }
  const std::optional<Eigen::Vector3d> chosen = followedCandidate(camera, snap.position, candidates, motion_px);
  if (!chosen) return std::nullopt;
  return Direction{*chosen, snap.position, source};
}

std::optional<Eigen::Vector3d> constrainToLine(const ecs::Registry& registry, const Eigen::Vector3d& origin,
                                               const Eigen::Vector3d& direction, const std::optional<Snap>& snap,
                                               const view::Ray& ray) {
  const auto project = [&](const Eigen::Vector3d& point) -> Eigen::Vector3d {
    return origin + direction.dot(point - origin) * direction;
  };
  if (snap && snap->kind == Snap::Kind::kPlane) {
    if (const Segment* segment = registry.tryGet<Segment>(snap->source)) {
      const double facing = segment->plane.normal.dot(direction);
      if (std::abs(facing) > 1e-3) {
        const double t = segment->plane.normal.dot(segment->plane.centroid - origin) / facing;
        return origin + t * direction;
      }
    }
    return project(snap->position);
  }
  if (snap) return project(snap->position);
  // The line's point nearest the ray: both unit, w = origin - ray origin.
  const double b = direction.dot(ray.direction);
  const double denominator = 1.0 - b * b;
  if (denominator < 1e-9) return std::nullopt;
  const Eigen::Vector3d w = origin - ray.origin;
  const double s = (b * w.dot(ray.direction) - w.dot(direction)) / denominator;
  return origin + s * direction;
}

}  // namespace plumb::viewer
