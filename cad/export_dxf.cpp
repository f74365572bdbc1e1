#include "cad/export_dxf.h"

#include <Eigen/Geometry>

#include "cad/dxf_document.h"
#include "cad/polygon_mesh.h"
#include "cad/project_validation.h"
#include "engine/core/atomic_file.h"

namespace plumb::cad {
namespace {

void addFaces(DxfDocument& dxf, const char* layer, const TriangleMesh& mesh) {
  for (const auto& [a, b, c] : mesh.triangles)
    dxf.addFace(layer, mesh.positions[a], mesh.positions[b], mesh.positions[c]);
}

}  // namespace

void exportDxf(const Project& project, AtomicFile& out) {
  validateProject(project, out.path(), "not exporting an invalid project");
  // AutoCAD colour indices: yellow, blue, cyan, white, red.
  DxfDocument dxf(
      {{kDxfPolygonLayer, 2}, {kDxfPrismLayer, 5}, {kDxfSegmentLayer, 4}, {kDxfEdgeLayer, 7}, {kDxfCornerLayer, 1}});
  for (const Polygon& polygon : project.polygons) {
    const char* layer = polygon.isPrism() ? kDxfPrismLayer : kDxfPolygonLayer;
    addFaces(dxf, layer, prismMesh(polygon));
    const Eigen::Vector3d normal = polygonNormal(polygon.vertices);
    dxf.addPolyline(layer, polygon.vertices, normal);
    if (polygon.isPrism()) {
      std::vector<Eigen::Vector3d> top = polygon.vertices;
      for (Eigen::Vector3d& p : top) p += polygon.extrusion;
      dxf.addPolyline(layer, top, normal);
    }
  }
  for (const Segment& segment : project.segments) {
    const reco::PlaneOutline& outline = segment.outline;
    addFaces(dxf, kDxfSegmentLayer, outlineMesh(outline));
    const Eigen::Vector3d normal = outline.axis_u.cross(outline.axis_v).normalized();
    for (const auto& ring : outline.shape.rings) {
      std::vector<Eigen::Vector3d> world;
      world.reserve(ring.size());
      for (const Eigen::Vector2d& p : ring) world.push_back(outline.toWorld(p));
      if (world.size() >= 2) dxf.addPolyline(kDxfSegmentLayer, world, normal);
    }
  }
  for (const Edge& edge : project.edges) dxf.addLine(kDxfEdgeLayer, edge.start, edge.end);
  for (const Corner& corner : project.corners) dxf.addPoint(kDxfCornerLayer, corner.position);
  const std::string text = dxf.text();
  out.write(text.data(), text.size());
}

void exportDxf(const Project& project, const std::string& path) {
  AtomicFile file(path);
  exportDxf(project, file);
  file.commit();
}

}  // namespace plumb::cad
