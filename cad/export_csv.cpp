#include "cad/export_csv.h"

#include "cad/measurement.h"
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

void appendVector(std::string& line, const Eigen::Vector3d& v) {
  for (Eigen::Index axis = 0; axis < 3; ++axis) {
    line += ",";
    appendNumber(line, v[axis]);
  }
}

}  // namespace

void exportCsv(const Project& project, AtomicFile& out) {
  validateProject(project, out.path(), "not exporting an invalid project");
  std::string text = "id,name,x,y,z,segment_1,segment_2,segment_3,support_1,support_2,support_3\r\n";
  for (const Corner& corner : project.corners) {
    text += std::to_string(corner.id) + ",";
    appendField(text, corner.name);
    appendVector(text, corner.position);
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

void exportMeasurementsCsv(const Project& project, AtomicFile& out) {
  validateProject(project, out.path(), "not exporting an invalid project");
  std::string text =
      "id,name,kind,value,unit,perimeter_m,from_parallel_deg,from_x,from_y,from_z,to_x,to_y,to_z,source_1,source_2\r\n";
  for (const Measurement& measurement : project.measurements) {
    const MeasureValue value = measure(measurement.kind, measurement.terms);
    text += std::to_string(measurement.id) + ",";
    appendField(text, measurement.name);
    text += std::string(",") + measureKindName(measurement.kind) + ",";
    appendNumber(text, value.value);
    text += std::string(",") + measureUnit(measurement.kind) + ",";
    if (measurement.kind == MeasureKind::kArea) appendNumber(text, *value.second);
    text += ",";
    if (measurement.kind == MeasureKind::kBetweenPlanes) appendNumber(text, *value.second);
    appendVector(text, value.from);
    appendVector(text, value.to);
    for (std::size_t k = 0; k < 2; ++k) {
      text += ',';
      if (k < measurement.sources.size() && measurement.sources[k] != kNoItem) {
        text += std::to_string(measurement.sources[k]);
      }
    }
    text += "\r\n";
  }
  out.write(text.data(), text.size());
}

void exportMeasurementsCsv(const Project& project, const std::string& path) {
  AtomicFile file(path);
  exportMeasurementsCsv(project, file);
  file.commit();
}

}  // namespace plumb::cad
