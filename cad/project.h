#pragma once
// The document a surveyor saves and exports: what Plumb reconstructed and drew over one cloud.
//
// A Project is a plain value, independent of the viewer's ECS (ui/viewer/project_bridge converts
// both ways) and of any file format (cad/project_file reads and writes .plumbproj files,
// cad/export_* write CAD formats). Everything is in world coordinates, metres, double precision.
//
// Items refer to each other by id, never by index: ids are unique across all items of a project
// (segments, edges, corners, polygons, measurements, groups share one id space), positive, and stable across
// saves. 0 means "none".

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "engine/view/camera.h"
#include "engine/view/clip_region.h"
#include "reco/outline.h"
#include "reco/plane.h"

namespace plumb::cad {

using ItemId = std::uint64_t;
inline constexpr ItemId kNoItem = 0;

// A named set of items (a storey, a facade, "windows"). Items name their group by id.
struct Group {
  ItemId id = kNoItem;
  std::string name;
};

// A plane the grower found, with its outline (the regression polygon, paper section 3.6).
struct Segment {
  ItemId id = kNoItem;
  std::string name;
  ItemId group = kNoItem;
  reco::Plane plane;           // valid
  reco::PlaneOutline outline;  // may be empty (no rings)
};

// The intersection line of two segments over its support range (paper section 4.1).
struct Edge {
  ItemId id = kNoItem;
  std::string name;
  ItemId group = kNoItem;
  std::array<ItemId, 2> segments{};
  Eigen::Vector3d start = Eigen::Vector3d::Zero();
  Eigen::Vector3d end = Eigen::Vector3d::Zero();
};

// The intersection point of three segments (paper section 4.1), or a corner the user asked for
// from three selected segments where no points lie (issue 7, point 6).
struct Corner {
  ItemId id = kNoItem;
  std::string name;
  ItemId group = kNoItem;
  std::array<ItemId, 3> segments{};
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  std::array<double, 3> support{};  // the three segments' lambda2, m^2
};

// A drawn polygon: a simple, closed, planar ring (the last vertex joins the first, not repeated),
// at least three vertices. `plane` is the segment it was drawn on, or kNoItem for a free polygon.
// With a non-zero `extrusion` it is a closed prism: the ring, the ring moved by `extrusion`, and
// the side faces between them.
struct Polygon {
  ItemId id = kNoItem;
  std::string name;
  ItemId group = kNoItem;
  ItemId plane = kNoItem;
  std::vector<Eigen::Vector3d> vertices;
  Eigen::Vector3d extrusion = Eigen::Vector3d::Zero();

  bool isPrism() const { return !extrusion.isZero(0.0); }
};

// What a surveyor measured (issue 22, point 4), on the geometry it was taken on as it was then: a
// measurement is not associative, so regrowing or deleting a segment leaves it as it was. Its
// value is never stored but always computed from that geometry (cad/measurement.h), so a file
// cannot hold a value that disagrees with it.
enum class MeasureKind : std::uint8_t {
  kDistance,       // point, point: the distance between them
  kAngle,          // plane or line, plane or line: the angle between them, 0 to 90 degrees
  kPointToPlane,   // plane, point: the distance from the point to the plane
  kBetweenPlanes,  // plane, plane, near parallel: their distance apart (a room's width)
  kHeight,         // plane (a floor), point: the point's height above the floor, vertically
  kArea,           // polygon: its area and perimeter
};

// One thing a measurement was taken on.
struct MeasureTerm {
  enum class Kind : std::uint8_t { kPoint, kPlane, kLine, kPolygon };
  Kind kind = Kind::kPoint;
  // kPoint: the point. kPlane, kLine: the point of the plane or line where it was picked.
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  // kPlane: its unit normal. kLine: its unit direction. Otherwise zero.
  Eigen::Vector3d direction = Eigen::Vector3d::Zero();
  // kPolygon: its ring (as Polygon::vertices). Otherwise empty.
  std::vector<Eigen::Vector3d> ring;
};

struct Measurement {
  ItemId id = kNoItem;
  std::string name;
  ItemId group = kNoItem;
  MeasureKind kind = MeasureKind::kDistance;
  std::vector<MeasureTerm> terms;  // as `kind` asks (cad/measurement.h, measureProblem)
  // For each term, the item it was taken on (a segment, edge, corner or polygon), or kNoItem
  // (a point of the cloud, a typed point, an item deleted since). As many as terms.
  std::vector<ItemId> sources;
};

struct Project {
  // The cloud the project was made on: as the user gave it (absolute, or relative to the
  // project file's folder). May be empty (a project of the built-in demo records the demo path).
  std::string cloud_path;
  std::optional<view::Camera> camera;
  // The view's section (slice, clip box, planes) when one is on.
  std::optional<view::ClipSettings> section;
  std::vector<Group> groups;
  std::vector<Segment> segments;
  std::vector<Edge> edges;
  std::vector<Corner> corners;
  std::vector<Polygon> polygons;
  std::vector<Measurement> measurements;
};

}  // namespace plumb::cad
