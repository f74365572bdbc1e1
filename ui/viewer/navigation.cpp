#include "ui/viewer/navigation.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <utility>

#include "engine/view/camera_controls.h"

namespace plumb::viewer {
namespace {

constexpr double kClickSlopPx = 4.0;   // a press and release this close is a click
constexpr double kDoubleClickS = 0.4;  // two clicks this close in time and place are a double click
constexpr double kDoubleClickSlopPx = 6.0;
constexpr double kOrbitRadPerPx = 0.005;    // a drag across 1000 pixels turns by 5 radians
constexpr double kZoomPerWheelStep = 0.85;  // each wheel step brings the eye 15 % closer
constexpr double kLookRadPerPx = 0.003;

}  // namespace

Navigator::Navigator(const Eigen::Vector3d& bounds_min, const Eigen::Vector3d& bounds_max, int width_px, int height_px)
    : bounds_min_(bounds_min),
      bounds_max_(bounds_max),
      home_(view::presetCamera(view::ViewPreset::kIso, bounds_min, bounds_max, width_px, height_px)),
      camera_(home_) {
  fly_speed_m_s_ = std::max(0.5, 0.1 * (bounds_max - bounds_min).norm());
}

void Navigator::set(const view::Camera& camera) {
  if (view::findCameraProblem(camera)) return;  // a degenerate step (a zoom onto the eye): keep the last view
  camera_ = camera;
  changed_ = true;
  // Two clicks on different views are two clicks, wherever they fall on the screen: a click
  // after a view preset or a scripted look (which centre what is clicked) is not a double click.
  last_click_time_s_ = -1.0;
}

void Navigator::setViewport(int width_px, int height_px, int window_width_px) {
  if (width_px <= 0 || height_px <= 0) return;
  render_px_per_window_px_ = window_width_px > 0 ? static_cast<double>(width_px) / window_width_px : 1.0;
  if (camera_.viewport_width_px == width_px && camera_.viewport_height_px == height_px) return;
  // Not a change of view: a moving view renders at a lower resolution than a still one.
  camera_.viewport_width_px = home_.viewport_width_px = width_px;
  camera_.viewport_height_px = home_.viewport_height_px = height_px;
}

void Navigator::setCamera(const view::Camera& camera) {
  set(camera);
}

void Navigator::setHome(const view::Camera& camera) {
  view::Camera home = camera;
  home.viewport_width_px = camera_.viewport_width_px;
  home.viewport_height_px = camera_.viewport_height_px;
  home_ = home;
  set(home_);
}

void Navigator::showPreset(view::ViewPreset preset) {
  set(view::presetCamera(preset, bounds_min_, bounds_max_, camera_.viewport_width_px, camera_.viewport_height_px));
}

void Navigator::showElevation(const Eigen::Vector3d& point, const Eigen::Vector3d& normal, double height_m) {
  Eigen::Vector3d n = normal.normalized();
  if (n.dot(camera_.position - point) < 0.0) n = -n;
  view::Camera next = camera_;
  next.projection = view::Projection::kOrthographic;
  next.target = point;
  next.position = point + n * std::max((camera_.position - point).norm(), 1.0);
  Eigen::Vector3d up = Eigen::Vector3d::UnitZ() - n.z() * n;
  if (up.norm() < 0.1) up = camera_.up - camera_.up.dot(n) * n;  // a level plane: keep the view's turn
  if (up.norm() < 1e-6) up = n.unitOrthogonal();
  next.up = up.normalized();
  next.ortho_height_m = height_m;
  set(next);
}

void Navigator::home() {
  set(home_);
}

void Navigator::toggleOrthographic() {
  view::Camera next = camera_;
  const double distance = (camera_.target - camera_.position).norm();
  const double half_fov = camera_.fov_deg * M_PI / 360.0;
  if (camera_.projection == view::Projection::kPerspective) {
    // The same extent at the target's depth.
    next.projection = view::Projection::kOrthographic;
    next.ortho_height_m = 2.0 * distance * std::tan(half_fov);
  } else {
    next.projection = view::Projection::kPerspective;
    const double wanted = camera_.ortho_height_m / (2.0 * std::tan(half_fov));
    next.position = camera_.target - view::viewDirection(camera_) * wanted;
  }
  set(next);
}

void Navigator::toggleFly() {
  flying_ = !flying_;
  forward_ = back_ = left_ = right_ = up_ = down_ = fast_ = false;
}

void Navigator::focus(const Eigen::Vector3d& point) {
  view::Camera next = camera_;
  const double distance = (point - camera_.position).norm();
  next.target = point;
  if (next.projection == view::Projection::kPerspective) {
    next.position = point - (point - camera_.position).normalized() * std::max(0.5 * distance, 0.2);
  } else {
    next.position = point - view::viewDirection(camera_) * (camera_.target - camera_.position).norm();
    next.ortho_height_m *= 0.5;
  }
  set(next);
}

bool Navigator::takeChanged() {
  return std::exchange(changed_, false);
}

bool Navigator::handle(const InputEvent& event, const PickAt& pick) {
  switch (event.kind) {
    case InputEvent::Kind::kMouseButton:
      if (event.pressed) {
        press(event, pick);
        return false;
      }
      return release(event);
    case InputEvent::Kind::kMouseMove:
      move(event);
      return false;
    case InputEvent::Kind::kWheel: {
      if (flying_) {
        fly_speed_m_s_ *= std::pow(1.25, event.wheel_y);
        return false;
      }
      const std::optional<Eigen::Vector3d> under = pick(event.x, event.y);
      set(view::zoomToPoint(camera_, under.value_or(camera_.target), std::pow(kZoomPerWheelStep, event.wheel_y)));
      return false;
    }
    case InputEvent::Kind::kKey:
      key(event, pick);
      return false;
    default:
      return false;
  }
}

void Navigator::press(const InputEvent& event, const PickAt& pick) {
  if (drag_button_ >= 0) return;  // one drag at a time
  drag_button_ = event.button;
  press_x_ = last_x_ = event.x;
  press_y_ = last_y_ = event.y;
  travelled_px_ = 0.0;
  if (event.button == GLFW_MOUSE_BUTTON_LEFT) {
    drag_ = flying_ ? Drag::kLook : Drag::kOrbit;
    if (!flying_) pivot_ = pick(event.x, event.y).value_or(camera_.target);
  } else {
    drag_ = Drag::kPan;
  }
}

bool Navigator::release(const InputEvent& event) {
  if (event.button != drag_button_) return false;
  const bool click = event.button == GLFW_MOUSE_BUTTON_LEFT && travelled_px_ <= kClickSlopPx;
  drag_button_ = -1;
  drag_ = Drag::kNone;
  if (!click) return false;
  // Quick clicks at different places (a measurement from one corner to another) stay clicks.
  const bool same_place = std::hypot(event.x - last_click_x_, event.y - last_click_y_) <= kDoubleClickSlopPx;
  if (last_click_time_s_ >= 0.0 && clock_s_ - last_click_time_s_ <= kDoubleClickS && same_place) {
    last_click_time_s_ = -1.0;
    focus(pivot_);
    return false;
  }
  last_click_time_s_ = clock_s_;
  last_click_x_ = event.x;
  last_click_y_ = event.y;
  return true;
}

void Navigator::move(const InputEvent& event) {
  const double dx = event.x - last_x_, dy = event.y - last_y_;
  last_x_ = event.x;
  last_y_ = event.y;
  if (drag_ == Drag::kNone) return;
  travelled_px_ = std::max(travelled_px_, std::hypot(event.x - press_x_, event.y - press_y_));
  if (travelled_px_ <= kClickSlopPx) return;  // still a click
  switch (drag_) {
    case Drag::kOrbit:
      set(view::orbit(camera_, pivot_, -dx * kOrbitRadPerPx, dy * kOrbitRadPerPx));
      break;
    case Drag::kPan:
      set(view::pan(camera_, dx * render_px_per_window_px_, dy * render_px_per_window_px_));
      break;
    case Drag::kLook:
      set(view::fly(camera_, Eigen::Vector3d::Zero(), -dx * kLookRadPerPx, dy * kLookRadPerPx));
      break;
    case Drag::kNone:
      break;
  }
}

void Navigator::key(const InputEvent& event, const PickAt& pick) {
  const bool down = event.pressed;
  fast_ = (event.mods & GLFW_MOD_SHIFT) != 0;
  switch (event.key) {
    case GLFW_KEY_W:
      forward_ = down;
      return;
    case GLFW_KEY_S:
      back_ = down;
      return;
    case GLFW_KEY_A:
      left_ = down;
      return;
    case GLFW_KEY_D:
      right_ = down;
      return;
    case GLFW_KEY_Q:
      down_ = down;
      return;
    case GLFW_KEY_E:
      up_ = down;
      return;
    default:
      break;
  }
  if (!down) return;
  switch (event.key) {
    case GLFW_KEY_F:
      toggleFly();
      break;
    case GLFW_KEY_1:
      showPreset(view::ViewPreset::kTop);
      break;
    case GLFW_KEY_2:
      showPreset(view::ViewPreset::kFront);
      break;
    case GLFW_KEY_3:
      showPreset(view::ViewPreset::kSide);
      break;
    case GLFW_KEY_4:
      showPreset(view::ViewPreset::kIso);
      break;
    case GLFW_KEY_O:
      toggleOrthographic();
      break;
    case GLFW_KEY_H:
      home();
      break;
    case GLFW_KEY_PERIOD:
      if (const auto under = pick(last_x_, last_y_)) focus(*under);
      break;
    default:
      break;
  }
}

void Navigator::update(double delta_s) {
  clock_s_ += delta_s;
  if (!flying_) return;
  const Eigen::Vector3d direction(static_cast<double>(right_) - static_cast<double>(left_),
                                  static_cast<double>(up_) - static_cast<double>(down_),
                                  static_cast<double>(forward_) - static_cast<double>(back_));
  if (direction.isZero()) return;
  const double speed = fly_speed_m_s_ * (fast_ ? 4.0 : 1.0);
  set(view::fly(camera_, direction.normalized() * speed * delta_s, 0.0, 0.0));
}

}  // namespace plumb::viewer
