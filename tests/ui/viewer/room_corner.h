#pragma once
// A hand-made scene for the viewer's tool tests: three faces of a room's corner at the origin,
// 2 m each, as a grow would make them (segments with outlines, the x/y walls' edge, the corner),
// seen from inside, from (4, 3.5, 2.5):
//
//        z
//        |  wall x = 0 (y, z in [0, 2])
//        |______ y   wall y = 0 (x, z in [0, 2])
//       /           floor z = 0 (x, y in [0, 2])
//      x

#include <Eigen/Geometry>
#include <array>
#include <memory>

#include "engine/ecs/registry.h"
#include "engine/view/camera.h"
#include "engine/view/camera_controls.h"
#include "ui/viewer/components.h"

namespace plumb::viewer::fixtures {

struct RoomCorner {
  view::Camera camera;
  std::array<ecs::Entity, 3> segments{};  // the walls x = 0 and y = 0, the floor
  ecs::Entity edge, corner;

  Eigen::Vector2d pixelOf(const Eigen::Vector3d& world) const { return *view::pixelOf(camera, world); }
};

// A segment on the plane through `origin` spanned by unit u and v, its outline the square
// [0, size]^2 of (u, v).
inline ecs::Entity addSquareSegment(ecs::Registry& registry, const Eigen::Vector3d& origin, const Eigen::Vector3d& u,
                                    const Eigen::Vector3d& v, double size) {
  Segment segment;
  segment.plane.valid = true;
  segment.plane.normal = u.cross(v).normalized();
  segment.plane.tangent = u;
  segment.plane.bitangent = v;
  segment.plane.centroid = origin + 0.5 * size * (u + v);
  segment.plane.offset = -segment.plane.normal.dot(origin);
  auto outline = std::make_shared<reco::PlaneOutline>();
  outline->origin = origin;
  outline->axis_u = u;
  outline->axis_v = v;
  outline->shape.vertices = {{0, 0}, {size, 0}, {size, size}, {0, size}};
  outline->shape.triangles = {{0, 1, 2}, {0, 2, 3}};
  outline->shape.rings = {outline->shape.vertices};
  outline->shape.area_m2 = size * size;
  segment.outline = outline;
  segment.name = "square";
  const ecs::Entity entity = registry.create();
  registry.emplace(entity, std::move(segment));
  return entity;
}

inline RoomCorner makeRoomCorner(ecs::Registry& registry) {
  RoomCorner room;
  room.camera.position = {4.0, 3.5, 2.5};
  room.camera.target = {0.5, 0.5, 0.5};
  room.camera.viewport_width_px = 800;
  room.camera.viewport_height_px = 600;
  const std::array<Eigen::Vector3d, 3> normals{Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY(),
                                               Eigen::Vector3d::UnitZ()};
  for (std::size_t i = 0; i < 3; ++i) {
    room.segments[i] =
        addSquareSegment(registry, Eigen::Vector3d::Zero(), normals[(i + 1) % 3], normals[(i + 2) % 3], 2.0);
  }
  room.edge = registry.create();
  registry.emplace(room.edge, Edge{{room.segments[0], room.segments[1]}, {0, 0, 0.2}, {0, 0, 1.8}, {0, 0, 1}, 100});
  room.corner = registry.create();
  registry.emplace(room.corner,
                   Corner{{room.segments[0], room.segments[1], room.segments[2]}, {0, 0, 0}, {}, "corner"});
  return room;
}

}  // namespace plumb::viewer::fixtures
