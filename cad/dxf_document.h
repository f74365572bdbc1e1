#pragma once
// An ASCII DXF drawing, release 2000 (AC1015), with what AutoCAD, LibreCAD and ezdxf need of it
// and no more: the HEADER ($ACADVER, $HANDSEED, units in metres, extents), empty CLASSES, the
// TABLES every R2000 file must have (VPORT *ACTIVE framing the extents, LTYPE ByBlock ByLayer
// Continuous, LAYER 0 and the drawing's layers, STYLE Standard, empty VIEW and UCS, APPID ACAD,
// DIMSTYLE Standard, BLOCK_RECORD *Model_Space and *Paper_Space), their two empty BLOCKS, the
// ENTITIES and the OBJECTS root dictionary with its ACAD_GROUP dictionary. Every object has a
// handle (group 5, 105 for DIMSTYLE) and its owner's (group 330); entities belong to model space.
//
// Entities: 3DFACE (triangles), LWPOLYLINE (closed planar rings, in the object coordinate system
// of their plane by the DXF arbitrary axis algorithm), LINE, POINT; all by layer (colour,
// linetype). Coordinates in world units with every digit of the double (cad/number_text.h).
//
// Not thread-safe: one thread builds one document.

#include <Eigen/Core>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace plumb::cad {

struct DxfLayer {
  std::string name;  // letters, digits, '_', '-' (asserted)
  int colour = 7;    // AutoCAD colour index, 1 to 255
};

// The object coordinate system of the DXF arbitrary axis algorithm for a unit extrusion
// direction `normal`: the x and y axes in world coordinates; (x, y, normal) is right-handed.
struct DxfOcs {
  Eigen::Vector3d x_axis;
  Eigen::Vector3d y_axis;
};
DxfOcs dxfOcs(const Eigen::Vector3d& normal);

class DxfDocument {
 public:
  // The drawing's layers, besides layer 0 which every drawing has.
  explicit DxfDocument(std::vector<DxfLayer> layers);

  // Entities on `layer`, which must be one of the constructor's (asserted). Coordinates must be
  // finite (asserted).
  void addFace(std::string_view layer, const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c);
  // A LWPOLYLINE through `ring` (at least 2 vertices), closed (the last vertex joins the first)
  // unless `closed` is false: its extrusion direction is the unit `normal`, its elevation the mean
  // of the vertices' heights along it, its vertices their OCS x and y. A vertex off the plane by d
  // moves onto it by d.
  void addPolyline(std::string_view layer, std::span<const Eigen::Vector3d> ring, const Eigen::Vector3d& normal,
                   bool closed = true);
  void addLine(std::string_view layer, const Eigen::Vector3d& start, const Eigen::Vector3d& end);
  void addPoint(std::string_view layer, const Eigen::Vector3d& position);

  // The whole file. May be called more than once.
  std::string text() const;

 private:
  std::string entityStart(std::string_view type, std::string_view layer, std::string_view subclass);
  void extend(const Eigen::Vector3d& p);

  std::vector<DxfLayer> layers_;
  std::string entities_;       // the ENTITIES section's content
  std::uint64_t next_handle_;  // the first handle no object has
  Eigen::Vector3d min_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d max_ = Eigen::Vector3d::Zero();
  bool empty_ = true;
};

}  // namespace plumb::cad
