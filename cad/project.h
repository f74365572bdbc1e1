#pragma once
// The document a surveyor saves and exports: what Plumb reconstructed and drew over one cloud.
//
// A Project is a plain value, independent of the viewer's ECS (ui/viewer/project_bridge converts
// both ways) and of any file format (cad/project_file reads and writes .plumbproj files,
// cad/export_* write CAD formats). Everything is in world coordinates, metres, double precision.
//
// Items refer to each other by id, never by index: ids are unique across all items of a project
// (segments, edges, corners, polygons, groups share one id space), positive, and stable across
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
};

}  // namespace plumb::cad
