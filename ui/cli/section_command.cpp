// plumb section: the floor plan of a project at a height (cad/floor_plan.h), without a window:
// its grown walls cut by a horizontal plane, written as a 2D DXF and SVG. All the outputs asked
// for or none of them.

#include <CLI/App.hpp>
#include <CLI/Config.hpp>
#include <CLI/Formatter.hpp>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>

#include "cad/floor_plan.h"
#include "cad/project_file.h"
#include "engine/core/atomic_file.h"
#include "engine/core/error.h"
#include "ui/cli/arguments.h"
#include "ui/cli/command.h"

namespace plumb::cli {
namespace {

struct SectionOptions {
  std::string project;
  double height_m = NAN;
  bool relative = false;
  std::string dxf;
  std::string svg;
  cad::FloorPlanOptions plan;
};

// The lowest point of the project's floors: the segments facing up or down, their outlines'
// vertices. The height of a section is typed above it (--above-floor).
double floorHeight(const cad::Project& project) {
  double lowest = INFINITY;
  for (const cad::Segment& segment : project.segments) {
    if (std::abs(segment.plane.normal.z()) < 0.99) continue;
    for (const auto& ring : segment.outline.shape.rings) {
      for (const auto& p : ring) lowest = std::min(lowest, segment.outline.toWorld(p).z());
    }
  }
  if (!std::isfinite(lowest)) throw Error("--above-floor: the project has no floor (no grown horizontal segment)");
  return lowest;
}

}  // namespace

Command addSectionCommand(CLI::App& plumb) {
  auto options = std::make_shared<SectionOptions>();
  CLI::App* sub = plumb.add_subcommand(
      "section", "The floor plan of a project: its grown walls cut at a height, as 2D DXF and SVG drawings");
  sub->footer(
      "Example: plumb section site.plumbproj --height 1.2 --above-floor --dxf plan.dxf --svg plan.svg\n"
      "The walls are the vertical segments; each is cut where its outline reaches, gaps of --min-opening or "
      "wider are openings, and faces meet at their planes' intersections (docs/floor-plans.md).");
  sub->add_option("project", options->project, "A project file (.plumbproj, docs/project-file.md)")->required();
  sub->add_option("--height", options->height_m, "The section's height: world z in metres")
      ->required()
      ->check(finiteIn(-1e7, 1e7));
  sub->add_flag("--above-floor", options->relative,
                "--height is above the project's lowest floor (its lowest horizontal segment) instead of world z");
  sub->add_option("--dxf", options->dxf, "A 2D DXF (R2000) drawing: layers PLAN_WALLS and PLAN_OPENINGS")
      ->type_name("FILE");
  sub->add_option("--svg", options->svg, "An SVG drawing to scale (1 unit = 1 mm)")->type_name("FILE");
  sub->add_option("--min-opening", options->plan.min_opening_m, "Gaps this wide or wider are openings, metres")
      ->check(finiteIn(0.0, 100.0))
      ->capture_default_str();
  sub->add_option("--join-gap", options->plan.join_gap_m,
                  "The most a wall's end moves to meet another wall at their planes' intersection, metres")
      ->check(finiteIn(0.0, 100.0))
      ->capture_default_str();
  sub->add_option("--join-reach", options->plan.join_reach_m,
                  "The most a wall's outer end moves to a corner when no other wall lies across the gap, metres "
                  "(0: as --join-gap)")
      ->check(finiteIn(0.0, 100.0))
      ->capture_default_str();

  auto run = [options]() -> int {
    if (options->dxf.empty() && options->svg.empty()) throw Error("nothing to write: give --dxf, --svg or both");
    if (!options->dxf.empty() && !options->svg.empty() && sameFile(options->dxf, options->svg)) {
      throw fileError(options->dxf, "--dxf and --svg both name this file: give each its own");
    }
    for (const std::string* output : {&options->dxf, &options->svg}) {
      if (!output->empty() && sameFile(*output, options->project)) {
        throw fileError(*output, "would overwrite the project");
      }
    }
    const cad::Project project = cad::readProjectFile(options->project);
    options->plan.height_m = options->height_m + (options->relative ? floorHeight(project) : 0.0);
    const cad::FloorPlan plan = cad::floorPlanAt(project, options->plan);

    // Opened first, so that a folder that does not exist fails before any file is written; all
    // or none are committed.
    std::unique_ptr<AtomicFile> dxf, svg;
    if (!options->dxf.empty()) dxf = std::make_unique<AtomicFile>(options->dxf);
    if (!options->svg.empty()) svg = std::make_unique<AtomicFile>(options->svg);
    if (dxf) {
      const std::string text = cad::floorPlanDxf(plan);
      dxf->write(text.data(), text.size());
      dxf->finish();
    }
    if (svg) {
      const std::string text = cad::floorPlanSvg(plan);
      svg->write(text.data(), text.size());
      svg->finish();
    }
    if (dxf) dxf->commit();
    if (svg) svg->commit();

    std::size_t closed = 0;
    for (const cad::PlanChain& chain : plan.chains) closed += chain.closed ? 1u : 0u;
    std::printf(
        "section at z = %.3f m: %zu wall faces cut, %zu lines, %zu corners joined, %zu closed outlines, "
        "%zu openings, %zu walls paired\n",
        plan.height_m, plan.wall_faces, plan.lines.size(), plan.joins, closed, plan.openings.size(), plan.walls.size());
    for (const cad::PlanWall& wall : plan.walls) {
      std::printf("  wall of segments %llu and %llu: %.1f mm thick\n", static_cast<unsigned long long>(wall.face_a),
                  static_cast<unsigned long long>(wall.face_b), wall.thickness_m * 1e3);
    }
    for (const cad::PlanOpening& opening : plan.openings) {
      std::printf("  opening in segment %llu: %.3f m wide\n", static_cast<unsigned long long>(opening.segment),
                  opening.width_m);
    }
    if (dxf) std::printf("wrote  %s\n", options->dxf.c_str());
    if (svg) std::printf("wrote  %s\n", options->svg.c_str());
    return 0;
  };
  return {sub, run};
}

}  // namespace plumb::cli
