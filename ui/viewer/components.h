#pragma once
// The viewer's ECS components (engine/ecs). Plain values; each names its one writer per frame.
//
//   Segment, Edge, Corner, SnapCandidate   written by SceneState::applyGrow (grow results)
//   Polygon                                written by SceneState's edits (the drawing tools' results)
//   Corner (three selected segments)       written by SceneState::addCornerOfSelected
//   Group, InGroup                         written by SceneState::groupSelected
//   Measurement                            written by SceneState::addMeasurement (the Measure tool)
//   Selection                              written by the segment list and the tools
//   ToolState                              written by the palette and DrawingTools (one entity holds it)

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "cad/project.h"
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
  std::string name;                 // "Corner N" for one made of three selected segments
};

// Something the cursor can snap to, drawn as a marker (corners, edge ends).
struct SnapCandidate {
  enum class Kind : std::uint8_t { kCorner, kEdge, kPlane, kPoint };
  Kind kind = Kind::kCorner;
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  ecs::Entity source = ecs::kNullEntity;  // the Corner or Edge entity
};

// A drawn polygon (world coordinates): a simple planar ring, on a segment's plane or free. With a
// non-zero extrusion it is a closed prism (the ring, the ring moved by it, and the sides).
struct Polygon {
  std::vector<Eigen::Vector3d> vertices;
  ecs::Entity plane = ecs::kNullEntity;  // the segment it was drawn on, or null
  std::string name;
  Eigen::Vector3d extrusion = Eigen::Vector3d::Zero();
};

// A measurement the Measure tool took (cad/measurement.h): its terms as they were when taken, and
// the items they were taken on.
struct Measurement {
  cad::MeasureKind kind = cad::MeasureKind::kDistance;
  std::vector<cad::MeasureTerm> terms;
  std::vector<ecs::Entity> sources;  // one per term: a Segment, Edge, Corner or Polygon; null for a point of the cloud
  std::string name;                  // "Distance 1", "Height 2", ...
};

// A named set of items; an item's InGroup names it.
struct Group {
  std::string name;
};
struct InGroup {
  ecs::Entity group = ecs::kNullEntity;
};

// Tag: the entity is selected.
struct Selection {};

enum class Tool : std::uint8_t { kNavigate, kGrow, kMeasure, kPolygon, kMove, kExtrude };

// The tools that draw and edit polygons (drawing_tools.h).
inline bool isDrawingTool(Tool tool) {
  return tool == Tool::kPolygon || tool == Tool::kMove || tool == Tool::kExtrude;
}

// The tool's name as the palette shows it and scripts name it (lower case there).
constexpr const char* toolName(Tool tool) {
  switch (tool) {
    case Tool::kNavigate:
      return "Navigate";
    case Tool::kGrow:
      return "Grow";
    case Tool::kMeasure:
      return "Measure";
    case Tool::kPolygon:
      return "Polygon";
    case Tool::kMove:
      return "Move/Copy";
    case Tool::kExtrude:
      return "Extrude";
  }
  return "";
}

// A direction in space that moves and extrusions follow (paper section 4.2, direction finding).
struct Direction {
  Eigen::Vector3d vector = Eigen::Vector3d::UnitZ();  // unit
  Eigen::Vector3d anchor = Eigen::Vector3d::Zero();   // where it was found, for the arrow
  const char* source = "";  // a string literal: "plane normal", "edge", "corner edge", "base to cursor"
};

// The drawing tools' state between clicks (ui/viewer/drawing_tools.h).
struct DrawingState {
  // Polygon: the vertices so far, and for each the segments it lies on (nothing for a point of
  // the cloud or a typed point); the polygon goes on the plane they all share.
  std::vector<Eigen::Vector3d> vertices;
  std::vector<std::optional<std::vector<ecs::Entity>>> vertex_segments;
  bool rectangle = false;  // a rectangle from three points instead of a free polygon
  // Move/Copy and Extrude: the polygon, and for Move the base point.
  ecs::Entity polygon = ecs::kNullEntity;
  std::optional<Eigen::Vector3d> base;
  bool copy = false;
  // Move/Copy: the last copy's original and offset, for "/N" (N - 1 more copies between them)
  // and "xN" (copies on to N times the offset).
  ecs::Entity copied_from = ecs::kNullEntity;
  Eigen::Vector3d copied_offset = Eigen::Vector3d::Zero();
  // Where the next click would put its point (snapped, then constrained), and the direction:
  // the pointer's (followed while unlocked) and the locked one (held Shift).
  std::optional<Eigen::Vector3d> preview;
  std::optional<Eigen::Vector3d> preview_extrusion;  // Extrude: the prism the click would make
  std::optional<Direction> direction;
  bool direction_locked = false;
  std::string typed;    // a distance being typed (metres), or after a copy "/N" or "xN"; Enter applies it
  std::string message;  // what the tool says (the next step, or why a click did nothing)
};

struct ToolState {
  Tool active = Tool::kGrow;
  // Measure (ui/viewer/measure_tool.h): the kind being taken, the terms clicked so far and the
  // items they came from, and what the tool last said (a result, or why a click took nothing).
  cad::MeasureKind measure_kind = cad::MeasureKind::kDistance;
  std::vector<cad::MeasureTerm> measure_terms;
  std::vector<ecs::Entity> measure_sources;
  std::string measure_message;
  // What the cursor snaps to now in a drawing tool (features only: a corner, an edge, a plane).
  std::optional<Snap> hover;
  DrawingState drawing;
};

}  // namespace plumb::viewer
