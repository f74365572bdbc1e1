#include "cad/export.h"

#include <array>
#include <filesystem>
#include <memory>

#include "cad/export_csv.h"
#include "cad/export_dxf.h"
#include "cad/export_gltf.h"
#include "cad/export_obj.h"
#include "engine/core/atomic_file.h"
#include "engine/core/error.h"

namespace plumb::cad {
namespace {

struct Format {
  std::string ExportTargets::*path;
  const char* name;
  void (*write)(const Project&, AtomicFile&);
};

constexpr std::array<Format, 5> kFormats{{{&ExportTargets::gltf, "glTF", exportGltf},
                                          {&ExportTargets::obj, "OBJ", exportObj},
                                          {&ExportTargets::dxf, "DXF", exportDxf},
                                          {&ExportTargets::csv, "CSV", exportCsv},
                                          {&ExportTargets::measurements, "measurements CSV", exportMeasurementsCsv}}};

// The same file, however it is spelt ("out.obj", "./out.obj").
std::filesystem::path comparable(const std::string& path) {
  std::error_code ignored;
  return std::filesystem::weakly_canonical(std::filesystem::absolute(path, ignored), ignored);
}

}  // namespace

std::vector<std::string> exportAll(const Project& project, const ExportTargets& targets) {
  std::vector<const Format*> asked;
  for (const Format& format : kFormats) {
    const std::string& path = targets.*format.path;
    if (path.empty()) continue;
    for (const Format* earlier : asked) {
      if (comparable(targets.*earlier->path) == comparable(path)) {
        throw fileError(path, std::string("the ") + earlier->name + " and the " + format.name +
                                  " export both name this file: give each its own");
      }
    }
    asked.push_back(&format);
  }

  // Opened first, so that a folder that does not exist fails before any work; a file destroyed
  // uncommitted removes its temporary.
  std::vector<std::unique_ptr<AtomicFile>> files;
  for (const Format* format : asked) files.push_back(std::make_unique<AtomicFile>(targets.*format->path));
  for (std::size_t i = 0; i < asked.size(); ++i) asked[i]->write(project, *files[i]);
  for (const auto& file : files) file->finish();
  std::vector<std::string> written;
  for (const auto& file : files) {
    file->commit();
    written.push_back(file->path());
  }
  return written;
}

}  // namespace plumb::cad
