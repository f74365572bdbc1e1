#pragma once
// ASCII DXF (release 2000, AC1015; cad/dxf_document.h) export of a project, for AutoCAD, LibreCAD,
// BricsCAD and whatever reads DXF. World coordinates in metres ($INSUNITS 6), every digit of each
// double. One layer per kind, each declared in the LAYER table:
//
//   PLUMB_POLYGONS  each polygon: a 3DFACE per triangle, its ring as a closed LWPOLYLINE
//   PLUMB_PRISMS    each prism: a 3DFACE per triangle of its closed mesh, its base and top rings
//                   as closed LWPOLYLINEs
//   PLUMB_SEGMENTS  each segment's outline: a 3DFACE per triangle, each ring as a closed
//                   LWPOLYLINE
//   PLUMB_EDGES     each edge: a LINE
//   PLUMB_CORNERS   each corner: a POINT
//
// An LWPOLYLINE lies in the object coordinate system of its plane (extrusion direction the ring's
// Newell normal, or the outline's axis_u x axis_v, by the DXF arbitrary axis algorithm), so CAD
// tools see it as one planar, editable polyline. DXF entities have no names: item names are not
// in the file (the glTF, OBJ and CSV exports keep them).

#include <string>

#include "cad/project.h"

namespace plumb {
class AtomicFile;
}

namespace plumb::cad {

inline constexpr const char* kDxfPolygonLayer = "PLUMB_POLYGONS";
inline constexpr const char* kDxfPrismLayer = "PLUMB_PRISMS";
inline constexpr const char* kDxfSegmentLayer = "PLUMB_SEGMENTS";
inline constexpr const char* kDxfEdgeLayer = "PLUMB_EDGES";
inline constexpr const char* kDxfCornerLayer = "PLUMB_CORNERS";

// Writes `project` to `out` without committing it. Throws plumb::Error naming out.path() when
// the project breaks a rule of findProjectProblem or the write fails.
void exportDxf(const Project& project, AtomicFile& out);

// Writes `project` to `path` atomically: on any error nothing appears there. Throws as above.
void exportDxf(const Project& project, const std::string& path);

}  // namespace plumb::cad
