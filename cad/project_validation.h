#pragma once
// The rules every Project follows, wherever it comes from (a project file, the viewer): the
// project file reader enforces them, its writer and the exporters require them.

#include <optional>
#include <string>
#include <string_view>

#include "cad/project.h"

namespace plumb::cad {

// What breaks a rule, and where: `place` as the JSON path of the value in a project file
// (docs/project-file.md), e.g. "polygons[2].vertices" or "edges[0].segments[1]".
struct ProjectProblem {
  std::string place;
  std::string what;  // a sentence a user can act on
};

// A direction's length may differ from 1 by this much.
inline constexpr double kUnitTolerance = 1e-6;

// The first rule `project` breaks, in the order below, or nothing when it follows them all:
// - the camera, if any, passes findCameraProblem;
// - every item's id is positive and no two items, of any kinds, share one;
// - a reference (an item's group, a polygon's plane, an edge's or corner's segments) is kNoItem or
//   the id of an item of the right kind (a group; a segment);
// - every number is finite; a segment's plane is valid, with unit normal, tangent and bitangent;
//   its outline's axes are perpendicular unit vectors and its triangles index its vertices;
// - a polygon's ring passes findPolygonProblem (cad/polygon_mesh.h, default tolerance), and a
//   prism's extrusion moves it off its plane by at least kPolygonResolution;
// - a measurement's terms pass measureProblem (cad/measurement.h), and it names one source per
//   term: kNoItem or a segment, edge, corner or polygon.
// O(items + vertices) plus findPolygonProblem's O(n^2) per polygon. Thread-safe.
std::optional<ProjectProblem> findProjectProblem(const Project& project);

// Throws plumb::Error "'<path>': <refusal>: field '<place>': <what>" when findProjectProblem finds
// a problem; `path` is the file being written, `refusal` e.g. "not exporting an invalid project".
void validateProject(const Project& project, const std::string& path, std::string_view refusal);

}  // namespace plumb::cad
