#pragma once
// Navigation as surveyors know it from Potree and CloudCompare, from InputEvents to a camera
// (the maths is engine/view/camera_controls.h):
//
//   left drag        orbit around the point under the cursor at the press (else the target)
//   right or middle  pan: what lies under the cursor follows it
//   wheel            zoom towards the point under the cursor
//   double click     focus: the view turns to the point and moves halfway to it (two clicks
//                    within 0.4 s and 6 pixels on a view that did not change between them)
//   F                fly mode on and off: W A S D move, Q E down and up, left drag looks around,
//                    Shift faster; the wheel changes the speed
//   1 2 3 4          top, front, side, iso views (orthographic but iso); O perspective and
//   H                orthographic; home: the view the cloud opened with
//
// Events and picks are in window pixels: a drag turns or pans the view as far whatever the
// render scale (dynamic resolution changes it while the view moves). Not thread-safe; the main
// thread owns it.

#include <Eigen/Core>
#include <functional>
#include <optional>

#include "engine/view/camera.h"
#include "engine/view/view_presets.h"
#include "ui/viewer/input_event.h"

namespace plumb::viewer {

// The world point under a window pixel, if any (the renderer's pick of the last frame).
using PickAt = std::function<std::optional<Eigen::Vector3d>(double x_px, double y_px)>;

class Navigator {
 public:
  // `bounds_min`, `bounds_max`: the cloud's box, for the standard views and the fly speed.
  Navigator(const Eigen::Vector3d& bounds_min, const Eigen::Vector3d& bounds_max, int width_px, int height_px);

  // Reacts to one event. A left click that did not move (press and release within a few pixels)
  // is not navigation: it returns true then, for the active tool to use.
  bool handle(const InputEvent& event, const PickAt& pick);
  // Moves a flying camera by the keys held for `delta_s` seconds; the clock of double clicks.
  void update(double delta_s);

  // The camera's viewport in render pixels, and the window's width in window pixels (events come in
  // window pixels; 0: the same as the viewport's).
  void setViewport(int width_px, int height_px, int window_width_px = 0);
  void setCamera(const view::Camera& camera);
  // Makes `camera` (viewport aside) the home view and shows it.
  void setHome(const view::Camera& camera);
  void showPreset(view::ViewPreset preset);
  // The elevation of a plane (a facade, a wall): orthographic, looking straight at the plane
  // through `point` from the side the view is on, `height_m` high, the vertical up (for a level
  // plane, the view's up: its plan).
  void showElevation(const Eigen::Vector3d& point, const Eigen::Vector3d& normal, double height_m);
  void home();
  void toggleOrthographic();
  void toggleFly();
  // Turns the view to `point` and halves the distance to it.
  void focus(const Eigen::Vector3d& point);

  const view::Camera& camera() const { return camera_; }
  bool flying() const { return flying_; }
  // Whether the camera changed since the last call (the renderer's cue to draw again).
  bool takeChanged();
  // A mouse button is held on the view (an orbit or pan in progress).
  bool dragging() const { return drag_button_ >= 0; }

 private:
  enum class Drag { kNone, kOrbit, kPan, kLook };
  void press(const InputEvent& event, const PickAt& pick);
  bool release(const InputEvent& event);
  void move(const InputEvent& event);
  void key(const InputEvent& event, const PickAt& pick);
  void set(const view::Camera& camera);

  Eigen::Vector3d bounds_min_, bounds_max_;
  view::Camera home_;
  view::Camera camera_;
  bool changed_ = true;
  bool flying_ = false;
  double fly_speed_m_s_ = 1.0;

  int drag_button_ = -1;
  Drag drag_ = Drag::kNone;
  Eigen::Vector3d pivot_ = Eigen::Vector3d::Zero();
  double press_x_ = 0.0, press_y_ = 0.0;
  double last_x_ = 0.0, last_y_ = 0.0;
  double travelled_px_ = 0.0;
  double render_px_per_window_px_ = 1.0;  // the camera's viewport over the window
  double last_click_time_s_ = -1.0;
  double last_click_x_ = 0.0, last_click_y_ = 0.0;
  double clock_s_ = 0.0;  // advanced by update(), for double clicks

  // Held keys of the fly mode.
  bool forward_ = false, back_ = false, left_ = false, right_ = false, up_ = false, down_ = false, fast_ = false;
};

}  // namespace plumb::viewer
