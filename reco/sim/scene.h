#pragma once
// The simulator's world: axis-aligned rectangles with rectangular holes, grouped into planes,
// plus the ground truth a scan of it must reproduce (planes, corners, edges) and the scanner
// stations. Scenes are built in a local frame (metres, z up) by SceneBuilder; the scanner
// rotates and offsets them into world coordinates.

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace plumb::reco::sim {

using PlaneId = std::uint32_t;
using MaterialId = std::uint16_t;

struct Material {
  std::string name;
  std::array<std::uint8_t, 3> rgb;
  double reflectivity;  // 0..1, scales the intensity
};

// An axis-aligned rectangle in the two coordinates of a plane other than its own axis:
// u = (axis + 1) % 3 and v = (axis + 2) % 3.
struct Rect2 {
  double u0, u1, v0, v1;
  bool contains(double u, double v) const { return u >= u0 && u <= u1 && v >= v0 && v <= v1; }
};

// A planar surface x[axis] = coord over `extent`, minus the holes holes[first_hole, +hole_count).
// Visible from both sides.
struct Quad {
  int axis;
  double coord;
  Rect2 extent;
  std::uint32_t first_hole;
  std::uint32_t hole_count;
  PlaneId plane;
  MaterialId material;
};

// A true plane: normal . x + offset = 0, the normal pointing into free space.
struct TruthPlane {
  PlaneId id;
  std::string name;
  Eigen::Vector3d normal;
  double offset;
};

// Where three planes meet at a real corner of the scene.
struct TruthCorner {
  Eigen::Vector3d position;
  std::array<PlaneId, 3> planes;
};

// Where two planes meet along a real edge of the scene, from start to end.
struct TruthEdge {
  Eigen::Vector3d start;
  Eigen::Vector3d end;
  std::array<PlaneId, 2> planes;
};

struct Scene {
  std::string name;
  std::vector<Material> materials;
  std::vector<Quad> quads;
  std::vector<Rect2> holes;
  std::vector<TruthPlane> planes;  // planes[id].id == id
  std::vector<TruthCorner> corners;
  std::vector<TruthEdge> edges;
  std::vector<Eigen::Vector3d> stations;  // possible scanner positions, the most useful first
  std::size_t default_station_count = 1;  // how many of them a scan uses unless told otherwise
};

// Rotation about the vertical axis and a translation: scene-local to world coordinates.
struct SceneFrame {
  double rotation_deg = 0.0;
  Eigen::Vector3d offset = Eigen::Vector3d::Zero();

  Eigen::Vector3d rotate(const Eigen::Vector3d& local) const;
  Eigen::Vector3d toWorld(const Eigen::Vector3d& local) const { return rotate(local) + offset; }
  TruthPlane toWorld(const TruthPlane& plane) const;
};

}  // namespace plumb::reco::sim
