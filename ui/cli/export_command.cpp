// plumb export: a project file to CAD formats (glTF, OBJ, DXF, CSV of the corners), all the
// outputs asked for or none of them.

#include <CLI/App.hpp>
#include <CLI/Config.hpp>
#include <CLI/Formatter.hpp>
#include <array>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <utility>

#include "cad/export.h"
#include "cad/project_file.h"
#include "engine/core/error.h"
#include "ui/cli/arguments.h"
#include "ui/cli/command.h"

namespace plumb::cli {
namespace {

std::string count(std::size_t n, const char* thing) {
  return std::to_string(n) + " " + thing + (n == 1 ? "" : "s");
}

struct ExportOptions {
  std::string project;
  cad::ExportTargets targets;
};

}  // namespace

Command addExportCommand(CLI::App& plumb) {
  auto options = std::make_shared<ExportOptions>();
  CLI::App* sub = plumb.add_subcommand("export", "Export a project to CAD formats: glTF, OBJ, DXF, CSV of the corners");
  sub->footer("Example: plumb export site.plumbproj --dxf site.dxf --csv corners.csv");
  sub->add_option("project", options->project, "A project file (.plumbproj, docs/project-file.md)")->required();
  cad::ExportTargets& parsed = options->targets;
  sub->add_option("--gltf", parsed.gltf, "A glTF 2.0 binary (.glb): meshes, edges as lines, corners as points")
      ->type_name("FILE");
  sub->add_option("--obj", parsed.obj, "A Wavefront OBJ file: one object per item")->type_name("FILE");
  sub->add_option("--dxf", parsed.dxf, "An ASCII DXF (R2000) drawing: one layer per kind of item")->type_name("FILE");
  sub->add_option("--csv", parsed.csv, "The corners as CSV: id, name, x, y, z, segments, support")->type_name("FILE");
  sub->add_option("--measurements", parsed.measurements,
                  "The measurements as CSV: id, name, kind, value, unit, perimeter, angle from parallel, "
                  "dimension line, sources")
      ->type_name("FILE");

  auto run = [options]() -> int {
    const cad::ExportTargets& targets = options->targets;
    const std::array<std::pair<const char*, const std::string*>, 5> outputs{
        {{"--gltf", &targets.gltf},
         {"--obj", &targets.obj},
         {"--dxf", &targets.dxf},
         {"--csv", &targets.csv},
         {"--measurements", &targets.measurements}}};
    bool any = false;
    for (const auto& [option, path] : outputs) {
      if (path->empty()) continue;
      any = true;
      if (sameFile(*path, options->project))
        throw fileError(*path, std::string(option) + " would overwrite the project");
    }
    if (!any) throw Error("nothing to export: give at least one of --gltf, --obj, --dxf, --csv, --measurements");

    const cad::Project project = cad::readProjectFile(options->project);
    // All or none: exportAll moves the outputs into place only once every one is complete.
    const std::vector<std::string> written = cad::exportAll(project, targets);

    std::size_t prisms = 0;
    for (const cad::Polygon& polygon : project.polygons) prisms += polygon.isPrism() ? 1u : 0u;
    std::printf("read   %s: %s, %s, %s, %s, %s, %s, %s\n", options->project.c_str(),
                count(project.segments.size(), "segment").c_str(), count(project.edges.size(), "edge").c_str(),
                count(project.corners.size(), "corner").c_str(),
                count(project.polygons.size() - prisms, "polygon").c_str(), count(prisms, "prism").c_str(),
                count(project.measurements.size(), "measurement").c_str(),
                count(project.groups.size(), "group").c_str());
    for (const std::string& path : written) {
      std::error_code ignored;
      std::printf("wrote  %s (%s bytes)\n", path.c_str(),
                  withThousands(std::filesystem::file_size(path, ignored)).c_str());
    }
    return 0;
  };
  return {sub, run};
}

}  // namespace plumb::cli
