#include "cad/export_csv.h"

#include "cad/number_text.h"
#include "cad/project_validation.h"
#include "engine/core/atomic_file.h"

namespace plumb::cad {
namespace {

void appendField(std::string& line, const std::string& field) {
  if (field.find_first_of(",\"\r\n") == std::string::npos) {
    line += field;
    return;
  }
  line += '"';
  for (const char c : field) line += c == '"' ? std::string("\"\"") : std::string(1, c);
  line += '"';
}

}  // namespace

void exportCsv(const Project& project, AtomicFile& out) {
  validateProject(project, out.path(), "not exporting an invalid project");
  std::string text = "id,name,x,y,z,segment_1,segment_2,segment_3,support_1,support_2,support_3\r\n";
  for (const Corner& corner : project.corners) {
    text += std::to_string(corner.id) + ",";
    appendField(text, corner.name);
    for (Eigen::Index axis = 0; axis < 3; ++axis) {
      text += ",";
      appendNumber(text, corner.position[axis]);
    }
    for (const ItemId segment : corner.segments) {
      text += ',';
      if (segment != kNoItem) text += std::to_string(segment);
    }
    for (const double support : corner.support) {
      text += ",";
      appendNumber(text, support);
    }
    text += "\r\n";
  }
  out.write(text.data(), text.size());
}

void exportCsv(const Project& project, const std::string& path) {
  AtomicFile file(path);
  exportCsv(project, file);
  file.commit();
}

}  // namespace plumb::cad
