#pragma once
// What the view keeps of a cloud (issue 22, clipping and slices): a box turned about the
// vertical whose inside, or outside, is kept, and any number of clip planes, each keeping the
// side its normal points to. A horizontal slice is two planes facing each other a thickness
// apart; an elevation's slab is the same about a picked plane.
//
// The splat draws only the points kept (shaders/splat.comp.glsl), so picking, which reads what
// was drawn, finds only them; node selection skips nodes wholly cut away, so the point budget
// goes to what is kept and a thin slab is drawn in full detail. keeps() is the same test on the
// host, for tests and for limiting grows to the region.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <optional>
#include <vector>

namespace plumb::view {

struct ClipBox {
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  Eigen::Vector3d half_size = Eigen::Vector3d::Ones();  // along the box's own axes, each > 0
  double yaw_rad = 0.0;                                 // the box's x axis turned from the world's about +z
};

struct ClipPlane {
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();  // the kept side; unit length
};

// A half-space n . x + d >= 0 in world coordinates.
using HalfSpace = Eigen::Vector4d;

// A region as half-spaces, made once and tested many times: node selection's cells each frame,
// the splat's plane buffer, every point a grow loads. The one place their tests are written.
struct ClipHalfSpaces {
  std::vector<HalfSpace> box_faces;  // a box's six faces, each keeping the inside; empty: no box
  bool keep_outside_box = false;
  std::vector<HalfSpace> planes;  // each must hold

  bool keeps(const Eigen::Vector3d& position) const;
  // Whether no point of the axis-aligned box from `min` to `max` can be kept: an octree node
  // there may be skipped. Conservative: false when unsure.
  bool cutsAway(const Eigen::Vector3d& min, const Eigen::Vector3d& max) const;
};

struct ClipRegion {
  std::optional<ClipBox> box;
  bool keep_outside_box = false;
  std::vector<ClipPlane> planes;

  // The shaders take this many planes, the box's six among them.
  static constexpr std::size_t kMaxPlanes = 32;

  bool active() const { return box.has_value() || !planes.empty(); }
  // Where the GPU's positions are taken from (relative positions keep float precision near it):
  // the box's centre, else the first plane's point, else the origin.
  Eigen::Vector3d anchor() const;
  ClipHalfSpaces halfSpaces() const;

  // For a test now and then; what tests many points or cells makes halfSpaces() once.
  bool keeps(const Eigen::Vector3d& position) const { return halfSpaces().keeps(position); }
  bool cutsAway(const Eigen::Vector3d& min, const Eigen::Vector3d& max) const {
    return halfSpaces().cutsAway(min, max);
  }
};

// A slab of `thickness` centred on the plane through `point` with `normal` (unit): an elevation's
// section of a facade or a wall.
struct ClipSlab {
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  Eigen::Vector3d normal = Eigen::Vector3d::UnitX();
  double thickness = 0.2;
};

// A region as a user states it (plumb render's and plumb view's options, the viewer's View
// panel): a horizontal slice, a slab about a plane, a box, planes; region() composes them.
struct ClipSettings {
  bool active() const { return slice || slab.has_value() || box.has_value() || !planes.empty(); }

  bool slice = false;
  double slice_bottom_z = 0.0, slice_thickness = 0.1;
  std::optional<ClipSlab> slab;
  std::optional<ClipBox> box;
  bool keep_outside_box = false;
  std::vector<ClipPlane> planes;

  ClipRegion region() const;
};

// Throws plumb::Error naming `what` for a region the renderer cannot take: a box of no or
// non-finite size, a plane without a finite unit normal, more than kMaxPlanes planes in all.
void checkClipRegion(const ClipRegion& region, const char* what);

// A horizontal slice: the points from `bottom_z` up to `bottom_z + thickness`.
ClipRegion horizontalSlice(double bottom_z, double thickness);
// A slab of `thickness` centred on a plane (an elevation of a facade): both sides within
// thickness / 2.
ClipRegion slabAbout(const Eigen::Vector3d& point, const Eigen::Vector3d& normal, double thickness);

}  // namespace plumb::view
