#pragma once
// The viewer's ECS components (engine/ecs). Plain values; each names its one writer per frame.
//
//   Segment, Edge, Corner, SnapCandidate   written by SceneState::applyGrow (grow results)
//   Polygon                                written by the drawing tools (issue 7)
//   Selection                              written by the segment list and the tools
//   ToolState                              written by the palette (one entity holds it)

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "engine/ecs/entity.h"
#include "reco/outline.h"
#include "reco/plane.h"
#include "ui/viewer/snapping.h"

namespace plumb::viewer {

// A plane the grower found, with what the segment list shows.
struct Segment {
  reco::Plane plane;
  std::shared_ptr<const reco::PlaneOutline> outline;  // may be null (no valid plane yet)
  std::uint64_t points = 0;
  double area_m2 = 0.0;    // of the outline
  double lambda2 = 0.0;    // the regression variance along the normal, m^2
  std::uint64_t grow = 0;  // the grow that made it
  std::string name;
  bool growing = false;  // true while its grow runs: the live outline
};

// The intersection line of two segments over its support range.
struct Edge {
  std::array<ecs::Entity, 2> segments;
  Eigen::Vector3d start = Eigen::Vector3d::Zero();
  Eigen::Vector3d end = Eigen::Vector3d::Zero();
  Eigen::Vector3d direction = Eigen::Vector3d::UnitX();
  std::uint32_t support_points = 0;
};

// The intersection point of three segments.
struct Corner {
  std::array<ecs::Entity, 3> segments;
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  std::array<double, 3> support{};  // the three lambda2, m^2
};

// Something the cursor can snap to, drawn as a marker (corners, edge ends).
struct SnapCandidate {
  enum class Kind : std::uint8_t { kCorner, kEdge, kPlane, kPoint };
  Kind kind = Kind::kCorner;
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  ecs::Entity source = ecs::kNullEntity;  // the Corner or Edge entity
};

// A drawn polygon (world coordinates), on a segment's plane or free.
struct Polygon {
  std::vector<Eigen::Vector3d> vertices;
  ecs::Entity plane = ecs::kNullEntity;
  std::string name;
};

// Tag: the entity is selected.
struct Selection {};

enum class Tool : std::uint8_t { kNavigate, kGrow, kMeasure };

struct ToolState {
  Tool active = Tool::kGrow;
  // Measure: the first snapped point, until the second.
  bool measure_started = false;
  Eigen::Vector3d measure_from = Eigen::Vector3d::Zero();
  Eigen::Vector3d measure_to = Eigen::Vector3d::Zero();
  Snap::Kind measure_from_kind = Snap::Kind::kPoint;
  Snap::Kind measure_to_kind = Snap::Kind::kPoint;
  bool measure_done = false;
  // What the cursor snaps to now in a drawing tool (features only: a corner, an edge, a plane).
  std::optional<Snap> hover;
};

}  // namespace plumb::viewer
