#include "ui/viewer/measure_tool.h"

#include <algorithm>
#include <vector>

#include "cad/measurement.h"
#include "engine/ecs/registry.h"
#include "ui/viewer/components.h"
#include "ui/viewer/drawing_tools.h"
#include "ui/viewer/scene_state.h"

namespace plumb::viewer {
namespace {

using cad::MeasureKind;
using TermKind = cad::MeasureTerm::Kind;

// The term kinds the next click may give, or nothing when the kind needs no more.
std::vector<TermKind> wantedNext(const ToolState& tool) {
  const std::vector<std::vector<TermKind>> wanted = cad::measureTermKinds(tool.measure_kind);
  return tool.measure_terms.size() < wanted.size() ? wanted[tool.measure_terms.size()] : std::vector<TermKind>{};
}

bool wants(const std::vector<TermKind>& kinds, TermKind kind) {
  return std::find(kinds.begin(), kinds.end(), kind) != kinds.end();
}

// Whether a measurement of `kind` keeps its first term for the next (one floor, many heights).
bool keepsFirstTerm(MeasureKind kind) {
  return kind == MeasureKind::kHeight || kind == MeasureKind::kPointToPlane;
}

}  // namespace

void forgetMeasureTerms(ToolState& tool) {
  tool.measure_terms.clear();
  tool.measure_sources.clear();
  tool.measure_message.clear();
}

void MeasureTool::setKind(cad::MeasureKind kind) {
  scene_.registry().patch<ToolState>(scene_.toolEntity(), [&](ToolState& tool) {
    tool.measure_kind = kind;
    forgetMeasureTerms(tool);
  });
}

void MeasureTool::escape() {
  scene_.registry().patch<ToolState>(scene_.toolEntity(), [&](ToolState& tool) { forgetMeasureTerms(tool); });
}

SnapOptions MeasureTool::snapOptionsFor(const ToolState& tool) {
  const std::vector<TermKind> kinds = wantedNext(tool);
  SnapOptions options;
  if (!wants(kinds, TermKind::kPoint)) {
    options.corners = false;
    options.edges = wants(kinds, TermKind::kLine);
    options.planes = wants(kinds, TermKind::kPlane);
    options.edge_on_planes = options.planes;  // a wall in a plan view: its plane is what counts
  }
  return options;
}

std::string MeasureTool::prompt(const ToolState& tool) {
  const bool first = tool.measure_terms.empty();
  switch (tool.measure_kind) {
    case MeasureKind::kDistance:
      return first ? "Click the first point" : "Click the second point";
    case MeasureKind::kAngle:
      return first ? "Click a plane or an edge" : "Click a second plane or edge";
    case MeasureKind::kPointToPlane:
      return first ? "Click a plane" : "Click a point: its distance to the plane (Escape: another plane)";
    case MeasureKind::kBetweenPlanes:
      return first ? "Click a plane" : "Click a plane parallel to it";
    case MeasureKind::kHeight:
      return first ? "Click the floor" : "Click a point: its height above the floor (Escape: another floor)";
    case MeasureKind::kArea:
      return "Click a polygon";
  }
  return "";
}

void MeasureTool::click(const view::Camera& camera, double x_px, double y_px, const PointPicker& pick_point) {
  // A term kept from before (a height's floor) whose item an undo or a deletion took away goes too.
  const ToolState& before = scene_.tool();
  const bool gone = std::any_of(before.measure_sources.begin(), before.measure_sources.end(),
                                [&](ecs::Entity e) { return e != ecs::kNullEntity && !scene_.registry().alive(e); });
  if (gone) escape();
  const ToolState& tool = scene_.tool();
  const std::vector<TermKind> kinds = wantedNext(tool);
  const auto say = [&](std::string message) {
    scene_.registry().patch<ToolState>(scene_.toolEntity(), [&](ToolState& t) { t.measure_message = message; });
  };
  if (wants(kinds, TermKind::kPolygon)) {
    const ecs::Entity polygon = polygonAt(scene_.registry(), camera, x_px, y_px);
    if (polygon == ecs::kNullEntity) return say("no polygon there: draw one with the Polygon tool");
    return take({TermKind::kPolygon, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(),
                 scene_.registry().get<Polygon>(polygon).vertices},
                polygon);
  }
  const bool point = wants(kinds, TermKind::kPoint);
  const std::optional<Snap> snap =
      snapCursor(scene_.registry(), camera, x_px, y_px, point ? pick_point : nullptr, snapOptionsFor(tool));
  if (!snap) {
    return say(point                           ? "nothing there to measure"
               : wants(kinds, TermKind::kLine) ? "no plane or edge there: grow one first"
                                               : "no plane there: grow one first");
  }
  if (point) return take({TermKind::kPoint, snap->position, Eigen::Vector3d::Zero(), {}}, snap->source);
  if (snap->kind == Snap::Kind::kEdge) {
    const Edge& edge = scene_.registry().get<Edge>(snap->source);
    const Eigen::Vector3d along = edge.end - edge.start;
    const Eigen::Vector3d direction = along.norm() > 0.0 ? Eigen::Vector3d(along.normalized()) : edge.direction;
    return take({TermKind::kLine, snap->position, direction, {}}, snap->source);
  }
  const Segment& segment = scene_.registry().get<Segment>(snap->source);
  take({TermKind::kPlane, snap->position, segment.plane.normal.normalized(), {}}, snap->source);
}

// Adds `term`; with the last one the kind needs, measures (or says why not).
void MeasureTool::take(const cad::MeasureTerm& term, ecs::Entity source) {
  ToolState tool = scene_.tool();
  // One plane or edge twice is no angle and no width.
  const bool between = tool.measure_kind == MeasureKind::kAngle || tool.measure_kind == MeasureKind::kBetweenPlanes;
  if (between && source != ecs::kNullEntity && !tool.measure_sources.empty() && tool.measure_sources.back() == source) {
    scene_.registry().patch<ToolState>(
        scene_.toolEntity(), [&](ToolState& t) { t.measure_message = "the same plane twice: click another"; });
    return;
  }
  tool.measure_terms.push_back(term);
  tool.measure_sources.push_back(source);
  tool.measure_message.clear();
  if (tool.measure_kind == MeasureKind::kHeight && tool.measure_terms.size() == 1) {
    // Refuse a wall as the floor now, not at the next point: measured against its own point.
    const cad::MeasureTerm here{TermKind::kPoint, term.point, Eigen::Vector3d::Zero(), {}};
    if (const auto problem = cad::measureProblem(MeasureKind::kHeight, {term, here})) {
      scene_.registry().patch<ToolState>(scene_.toolEntity(),
                                         [&](ToolState& t) { t.measure_message = "not a floor: " + *problem; });
      return;
    }
  }
  if (tool.measure_terms.size() == cad::measureTermKinds(tool.measure_kind).size()) {
    if (const auto problem = cad::measureProblem(tool.measure_kind, tool.measure_terms)) {
      // The terms before stay: the next click tries another last one.
      tool.measure_message = "not measured: " + *problem;
      tool.measure_terms.pop_back();
      tool.measure_sources.pop_back();
    } else {
      const ecs::Entity made = scene_.addMeasurement(tool.measure_kind, tool.measure_terms, tool.measure_sources);
      const Measurement& measurement = scene_.registry().get<Measurement>(made);
      tool.measure_message = measurement.name + ": " +
                             cad::measureText(measurement.kind, cad::measure(measurement.kind, measurement.terms));
      // A height keeps its floor for the next point.
      const std::size_t keep = keepsFirstTerm(tool.measure_kind) ? 1 : 0;
      tool.measure_terms.resize(keep);
      tool.measure_sources.resize(keep);
    }
  }
  scene_.registry().patch<ToolState>(scene_.toolEntity(), [&](ToolState& t) { t = std::move(tool); });
}

}  // namespace plumb::viewer
