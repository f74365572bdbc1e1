#pragma once
// The drawing tools of paper section 4.2 over the viewer's scene:
//
//   Polygon    clicks add snapped vertices; clicking the first vertex (or Enter) closes it.
//              Vertices snapped to features of one segment put the polygon on that segment's
//              plane (and between them the pointer's ray meets that plane, so a polygon can be
//              drawn where points are missing); otherwise it is free in 3D and must be planar.
//              As a rectangle: two clicks give one side, the third its width.
//   Move/Copy  a click picks a polygon, the next the base point, the next the target; Copy
//              leaves the original, and the copy becomes the one the next target moves on from
//              (so repeated clicks copy a step up a staircase); then "/N" Enter puts N - 1 more
//              copies evenly between the original and the copy, "xN" continues to N copies.
//   Extrude    a click picks a polygon, the next the target its top face passes through: a
//              closed prism along the polygon's normal or the locked direction.
//
// Every tool follows the direction the pointer finds (direction_finding.h); a held Shift locks
// it, and the tool's next point is then constrained to the line along it (in Move/Copy, between
// the base point and a corner or vertex the direction is the one from base to cursor). A number
// typed before Enter is a distance along the direction (locked, or towards the cursor).
//
// The tools' state between clicks is ToolState::drawing; what they make are SceneState edits,
// each undoable. Input arrives snapped (Pointer), so the tools are plain logic: unit tests drive
// them without a window.

#include <Eigen/Core>
#include <optional>

#include "engine/view/camera.h"
#include "engine/view/camera_controls.h"
#include "ui/viewer/snapping.h"

namespace plumb::viewer {

class SceneState;
struct DrawingState;

// What a drawing tool knows of the pointer: its snap (a click adds the cloud's point under it),
// its ray, its pixel and its latest movement (render pixels).
struct Pointer {
  std::optional<Snap> snap;
  view::Ray ray;
  Eigen::Vector2d pixel = Eigen::Vector2d::Zero();
  Eigen::Vector2d motion_px = Eigen::Vector2d::Zero();
};

// On the main thread only (the ECS's); `scene` must outlive the tools. Calls while the active tool
// is not Polygon, Move/Copy or Extrude change nothing but the direction.
class DrawingTools {
 public:
  explicit DrawingTools(SceneState& scene) : scene_(scene) {}

  // Every frame: the preview of the next point, and (unless locked) the direction.
  void hover(const Pointer& pointer, const view::Camera& camera);
  // A left click in the view in the active tool (Polygon, Move or Extrude).
  void click(const Pointer& pointer, const view::Camera& camera);
  // Shift pressed (true) or released.
  void lockDirection(bool locked);
  // A character of a typed distance (digits, '.', '-') or copy count ('/', 'x', '*' first);
  // others are ignored.
  void type(char character);
  // Takes back the last typed character, or the polygon's last vertex.
  void backspace();
  // Applies a typed distance, or closes the polygon being drawn.
  void enter(const Pointer& pointer, const view::Camera& camera);
  // Drops what the tool has begun.
  void escape();
  // Forgets everything (the tool changes); Copy stays as it was.
  void reset();

 private:
  template <class F>
  void edit(F&& change);
  const DrawingState& state() const;
  std::optional<Eigen::Vector3d> constraintOrigin() const;
  std::optional<Eigen::Vector3d> target(const Pointer& pointer) const;
  std::optional<Eigen::Vector3d> typedTarget(const Pointer& pointer) const;
  std::optional<Eigen::Vector3d> extrusionDirection() const;
  std::optional<Eigen::Vector3d> extrusionTo(const Eigen::Vector3d& target) const;
  void updateDirection(const Pointer& pointer, const view::Camera& camera);
  void polygonPoint(const Eigen::Vector3d& point, const Pointer& pointer, const view::Camera& camera, bool typed);
  void forgetVanishedPolygon();
  void closePolygon();
  void moveTo(const Eigen::Vector3d& point);
  void copyArray();
  void extrudeTo(const Eigen::Vector3d& point);
  void pickPolygon(const Pointer& pointer, const view::Camera& camera);

  SceneState& scene_;
};

// The drawn polygon under pixel (x, y) of `camera`: the nearest whose face contains the pixel, or
// whose side passes within `radius_px`; null when none.
ecs::Entity polygonAt(const ecs::Registry& registry, const view::Camera& camera, double x_px, double y_px,
                      double radius_px = 8.0);

}  // namespace plumb::viewer
