#pragma once
// Several exports of one project that appear together or not at all: what `plumb export` and the
// viewer's Export button write (cad/export_gltf.h, export_obj.h, export_dxf.h, export_csv.h; both CSV files).

#include <string>
#include <vector>

#include "cad/project.h"

namespace plumb::cad {

// Where each format goes; an empty path skips the format.
struct ExportTargets {
  std::string gltf;          // glTF 2.0 binary (.glb)
  std::string obj;           // Wavefront OBJ
  std::string dxf;           // ASCII DXF R2000
  std::string csv;           // the corners as CSV
  std::string measurements;  // the measurements as CSV
};

// Writes every format `targets` names. Each output is opened, written and flushed through its own
// AtomicFile before any is moved into place, so that on any error (an invalid project, a folder
// that does not exist, a full disk) none of them appears and files already at those paths stay as
// they were. Returns the paths written, in the order gltf, obj, dxf, csv, measurements (empty when `targets`
// names none). Throws plumb::Error naming the file concerned: that of the first output that
// fails, or one that two formats name. Thread-safe for distinct paths.
std::vector<std::string> exportAll(const Project& project, const ExportTargets& targets);

}  // namespace plumb::cad
