#pragma once
// Cursor snapping (paper section 4.2): what the pointer means in a drawing tool. In priority
// order, within a pixel radius: a corner or a drawn polygon's vertex (the nearer), a point on an
// edge within its support range, a point on the outline of a plane seen edge on (a wall in a
// plan view; when asked for), a point on a segment's plane inside its outline, a point of the
// cloud.
// Corners and edges come from the planes, not from the points, so a corner in a scan shadow is
// still a corner.

#include <Eigen/Core>
#include <functional>
#include <optional>

#include "engine/ecs/entity.h"
#include "engine/view/camera.h"

namespace plumb::ecs {
class Registry;
}

namespace plumb::viewer {

struct Snap {
  enum class Kind { kCorner, kVertex, kEdge, kPlane, kPoint };
  Kind kind = Kind::kPoint;
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  // world coordinates
  ecs::Entity source = ecs::kNullEntity;               // the Corner, Polygon, Edge or Segment; null for a point
  double distance_px = 0.0;                            // from the cursor to where the snap appears
};

const char* snapKindName(Snap::Kind kind);

struct SnapOptions {
  double radius_px = 12.0;  // corners and edges snap within this many pixels of the cursor
  // What may be snapped to (the cloud's points: when a picker is given). Measuring the distance to
  // a plane wants the plane, not the edge beside the cursor.
  bool corners = true;  // corners and polygon vertices
  bool edges = true;
  bool planes = true;
  // Planes seen edge on, near their outline's line: where a plane is what is wanted (selecting a
  // wall, measuring to it in a plan view), not a point (its height there is the outline's edge's).
  bool edge_on_planes = false;
};

// The cloud's point under a pixel, if any (the renderer's pick); may be empty.
using PointPicker = std::function<std::optional<Eigen::Vector3d>(double x_px, double y_px)>;

// What the cursor at (x, y) (pixels of `camera`'s viewport) snaps to in `registry` (Corner,
// Polygon, Edge and Segment components); `pick_point` is asked only when no feature is near. Nothing
// when nothing is there.
std::optional<Snap> snapCursor(const ecs::Registry& registry, const view::Camera& camera, double x_px, double y_px,
                               const PointPicker& pick_point, const SnapOptions& options = {});

}  // namespace plumb::viewer
