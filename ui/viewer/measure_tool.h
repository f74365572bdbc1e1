#pragma once
// The Measure tool (issue 22, point 4): each click gives the next term the chosen kind of
// measurement asks for (cad/measurement.h):
//
//   Distance        two snapped points (a corner, a vertex, a point on an edge or a plane, a point
//                   of the cloud)
//   Angle           two planes or edges (an edge within the snap radius, else the plane under the
//                   cursor)
//   Point to plane  a plane, then points
//   Between planes  a plane, then a second near-parallel one (a room's width)
//   Height          a floor, then points
//   Area            a drawn polygon
//
// The last term makes a Measurement, one undoable edit (SceneState::addMeasurement). A height and
// a point-to-plane distance keep their plane, so one floor serves every height after it until
// Escape. Terms the kind cannot measure (planes far from parallel, a wall as a floor) are refused
// with the reason, and the tool waits for another click. Plain logic over the scene: unit tests
// drive it without a window.

#include <string>

#include "cad/project.h"
#include "engine/view/camera.h"
#include "ui/viewer/snapping.h"

namespace plumb::viewer {

class SceneState;
struct ToolState;

// Forgets the Measure tool's terms and message (the tool changes, Escape, another kind).
void forgetMeasureTerms(ToolState& tool);

class MeasureTool {
 public:
  explicit MeasureTool(SceneState& scene) : scene_(scene) {}

  // Measures `kind` from now on, forgetting any terms clicked.
  void setKind(cad::MeasureKind kind);
  // A click at (x, y) (pixels of `camera`'s viewport); `pick_point` gives the cloud's point there.
  void click(const view::Camera& camera, double x_px, double y_px, const PointPicker& pick_point);
  // Forgets the terms clicked so far (Escape).
  void escape();

  // What the cursor may snap to for the next term (the hover marker shows it).
  static SnapOptions snapOptionsFor(const ToolState& tool);
  // The next step, as the panel says it: "Click the floor", ...
  static std::string prompt(const ToolState& tool);

 private:
  void take(const cad::MeasureTerm& term, ecs::Entity source);

  SceneState& scene_;
};

}  // namespace plumb::viewer
