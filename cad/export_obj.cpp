#include "cad/export_obj.h"

#include "cad/item_name.h"
#include "cad/number_text.h"
#include "cad/polygon_mesh.h"
#include "cad/project_validation.h"
#include "engine/core/atomic_file.h"

namespace plumb::cad {
namespace {

// OBJ names end at white space and '#' starts a comment.
std::string objName(const std::string& name, std::string_view kind, ItemId id) {
  std::string result = itemName(name, kind, id);
  for (char& c : result) {
    const auto byte = static_cast<unsigned char>(c);
    if (byte <= ' ' || byte == 0x7f || c == '#') c = '_';
  }
  return result;
}

class ObjWriter {
 public:
  void object(const std::string& name) { text_ += "o " + name + "\n"; }

  // The position's 1-based index.
  std::size_t vertex(const Eigen::Vector3d& p) {
    text_ += "v ";
    appendNumber(text_, p.x());
    text_ += ' ';
    appendNumber(text_, p.y());
    text_ += ' ';
    appendNumber(text_, p.z());
    text_ += '\n';
    return ++vertex_count_;
  }

  void mesh(const TriangleMesh& mesh) {
    const std::size_t base = vertex_count_ + 1;
    for (const Eigen::Vector3d& p : mesh.positions) vertex(p);
    for (const auto& [a, b, c] : mesh.triangles) {
      text_ += "f " + std::to_string(base + a) + " " + std::to_string(base + b) + " " + std::to_string(base + c) + "\n";
    }
  }

  void line(const Eigen::Vector3d& start, const Eigen::Vector3d& end) {
    const std::size_t a = vertex(start), b = vertex(end);
    text_ += "l " + std::to_string(a) + " " + std::to_string(b) + "\n";
  }

  void point(const Eigen::Vector3d& p) { text_ += "p " + std::to_string(vertex(p)) + "\n"; }

  const std::string& text() const { return text_; }

 private:
  std::string text_ =
      "# Plumb project, exported as Wavefront OBJ\n"
      "# World coordinates in metres, z up; faces counter-clockwise seen from outside\n";
  std::size_t vertex_count_ = 0;
};

}  // namespace

void exportObj(const Project& project, AtomicFile& out) {
  validateProject(project, out.path(), "not exporting an invalid project");
  ObjWriter obj;
  for (const Polygon& polygon : project.polygons) {
    obj.object(objName(polygon.name, "polygon", polygon.id));
    obj.mesh(prismMesh(polygon));
  }
  for (const Segment& segment : project.segments) {
    obj.object(objName(segment.name, "segment", segment.id));
    obj.mesh(outlineMesh(segment.outline));
  }
  for (const Edge& edge : project.edges) {
    obj.object(objName(edge.name, "edge", edge.id));
    obj.line(edge.start, edge.end);
  }
  for (const Corner& corner : project.corners) {
    obj.object(objName(corner.name, "corner", corner.id));
    obj.point(corner.position);
  }
  out.write(obj.text().data(), obj.text().size());
}

void exportObj(const Project& project, const std::string& path) {
  AtomicFile file(path);
  exportObj(project, file);
  file.commit();
}

}  // namespace plumb::cad
