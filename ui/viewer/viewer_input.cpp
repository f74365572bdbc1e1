// The viewer's input sources: the window's events (mouse, keys) and a session script's steps,
// both as InputEvents for the same tools. A headset's controllers are the third
// (viewer_xr.cpp).

#include "ui/viewer/viewer.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <array>
#include <cstdio>

#include "engine/view/camera_controls.h"

namespace plumb::viewer {

// The script's next frame: its settings applied, its steps as input events (steps at world
// points become window pixels in the view now). False when the session ends: the script is
// done, or a step failed (exit status 1).
bool Viewer::playScriptFrame(std::vector<InputEvent>& events, std::optional<std::string>& screenshot) {
  const bool grower_idle = cloud_ && !(cloud_->grow && cloud_->grow->busy());
  ScriptFrame frame = script_->next(grower_idle, cloud_ && streamingIdle());
  if (frame.failure) {
    std::fprintf(stderr, "plumb view: %s: %s\n", options_.script.c_str(), frame.failure->c_str());
    exit_status_ = 1;
    return false;
  }
  if (frame.finished) return false;
  events.insert(events.end(), frame.events.begin(), frame.events.end());
  if (frame.tool) setTool(*frame.tool);
  if (frame.measure) {
    setTool(Tool::kMeasure);
    measure_.setKind(*frame.measure);
  }
  if (frame.grow_detail) grow_panel_.detail = *frame.grow_detail;
  if (frame.colour) settings_.colour = static_cast<render::ColourMode>(*frame.colour);
  if (frame.resize) window_.resize(frame.resize->first, frame.resize->second);
  if (frame.look && cloud_) {
    view::Camera camera = cloud_->navigator->camera();
    camera.position = frame.look->first;
    camera.target = frame.look->second;
    camera.up = Eigen::Vector3d::UnitZ();  // level, whatever the view before
    cloud_->navigator->setCamera(camera);
  }
  // Steps at world points: their window pixels in the view now.
  const auto windowPixel = [&](const Eigen::Vector3d& world) -> std::optional<Eigen::Vector2d> {
    const std::optional<Eigen::Vector2d> pixel = view::pixelOf(cloud_->navigator->camera(), world);
    if (!pixel) {
      std::fprintf(stderr, "plumb view: %s: the world point of a step is behind the camera\n", options_.script.c_str());
      exit_status_ = 1;
      quit_ = true;
      return std::nullopt;
    }
    return Eigen::Vector2d(*pixel / renderScale());
  };
  const auto mouse = [](InputEvent::Kind kind, const Eigen::Vector2d& at, bool pressed = false) {
    return InputEvent{.kind = kind, .x = at.x(), .y = at.y(), .button = GLFW_MOUSE_BUTTON_LEFT, .pressed = pressed};
  };
  const std::array<std::pair<std::optional<Eigen::Vector3d>, bool>, 2> world_steps{
      {{frame.click_world, true}, {frame.move_world, false}}};
  for (const auto& [world, press] : world_steps) {
    if (!world || !cloud_) continue;
    const std::optional<Eigen::Vector2d> at = windowPixel(*world);
    if (!at) break;
    events.push_back(mouse(InputEvent::Kind::kMouseMove, *at));
    if (press) {
      events.push_back(mouse(InputEvent::Kind::kMouseButton, *at, true));
      events.push_back(mouse(InputEvent::Kind::kMouseButton, *at, false));
    }
  }
  if (frame.drag_world && cloud_ && !quit_) {
    const std::optional<Eigen::Vector2d> from = windowPixel(frame.drag_world->from);
    const std::optional<Eigen::Vector2d> to = from ? windowPixel(frame.drag_world->to) : std::nullopt;
    if (from && to) {
      events.push_back(mouse(InputEvent::Kind::kMouseMove, *from));
      events.push_back(mouse(InputEvent::Kind::kMouseButton, *from, true));
      for (int i = 1; i <= frame.drag_world->steps; ++i) {
        const double t = static_cast<double>(i) / frame.drag_world->steps;
        events.push_back(mouse(InputEvent::Kind::kMouseMove, *from + t * (*to - *from)));
      }
      events.push_back(mouse(InputEvent::Kind::kMouseButton, *to, false));
    }
  }
  if (quit_) return false;
  if (frame.memory) reportMemory(*frame.memory);
  screenshot = frame.screenshot;
  return true;
}

void Viewer::handleEvents(const std::vector<InputEvent>& events) {
  for (const InputEvent& event : events) {
    if (event.kind == InputEvent::Kind::kMouseMove || event.kind == InputEvent::Kind::kMouseButton) {
      mouse_x_ = event.x;
      mouse_y_ = event.y;
    }
    if (event.kind == InputEvent::Kind::kClose) {
      quit_ = true;
      continue;
    }
    const bool mouse = event.kind == InputEvent::Kind::kMouseMove || event.kind == InputEvent::Kind::kMouseButton ||
                       event.kind == InputEvent::Kind::kWheel;
    const bool keyboard = event.kind == InputEvent::Kind::kKey || event.kind == InputEvent::Kind::kCharacter;
    // The palette has the mouse unless a drag on the view is under way (a release must end it).
    const bool dragging = (cloud_ && cloud_->navigator->dragging()) || box_drag_.has_value();
    if (mouse && imgui_.wantsMouse() && !dragging) continue;
    if (keyboard && imgui_.wantsKeyboard()) continue;
    handleViewEvent(event);
  }
}

// Keys of the drawing tools: Shift locks the direction; while a tool has begun, digits, '.',
// '-', Backspace and Enter type a distance (and are not view presets). True when taken.
bool Viewer::drawingKey(const InputEvent& event) {
  if (event.kind == InputEvent::Kind::kKey && (event.key == GLFW_KEY_LEFT_SHIFT || event.key == GLFW_KEY_RIGHT_SHIFT)) {
    drawing_.lockDirection(event.pressed);
    return false;  // the navigator's fast flight sees Shift too
  }
  const DrawingState& d = scene_.tool().drawing;
  const bool begun = !d.vertices.empty() || d.base || d.polygon != ecs::kNullEntity;
  if (!isDrawingTool(scene_.tool().active) || !begun || !cloud_) return false;
  if (event.kind == InputEvent::Kind::kCharacter) {
    if (event.codepoint < 128) drawing_.type(static_cast<char>(event.codepoint));
    return true;
  }
  if (event.kind != InputEvent::Kind::kKey) return false;
  const bool typing = (event.key >= GLFW_KEY_0 && event.key <= GLFW_KEY_9) || event.key == GLFW_KEY_PERIOD ||
                      event.key == GLFW_KEY_MINUS || (event.key >= GLFW_KEY_KP_0 && event.key <= GLFW_KEY_KP_9) ||
                      event.key == GLFW_KEY_KP_DECIMAL || event.key == GLFW_KEY_KP_SUBTRACT ||
                      event.key == GLFW_KEY_SLASH || event.key == GLFW_KEY_KP_DIVIDE || event.key == GLFW_KEY_X ||
                      event.key == GLFW_KEY_KP_MULTIPLY;
  if (typing) return true;  // the character event that follows carries it
  if (!event.pressed) return false;
  if (event.key == GLFW_KEY_BACKSPACE) {
    drawing_.backspace();
    return true;
  }
  if (event.key == GLFW_KEY_ENTER || event.key == GLFW_KEY_KP_ENTER) {
    drawing_.enter(pointerAt(mousePointer(hovered_px_.x(), hovered_px_.y()), false), cloud_->navigator->camera());
    return true;
  }
  return false;
}

void Viewer::handleViewEvent(const InputEvent& event) {
  if (event.kind == InputEvent::Kind::kKey &&
      (event.key == GLFW_KEY_LEFT_CONTROL || event.key == GLFW_KEY_RIGHT_CONTROL)) {
    control_held_ = event.pressed;
  }
  if (event.kind == InputEvent::Kind::kKey && (event.key == GLFW_KEY_LEFT_SHIFT || event.key == GLFW_KEY_RIGHT_SHIFT)) {
    shift_held_ = event.pressed;
  }
  if (drawingKey(event)) return;
  if (event.kind == InputEvent::Kind::kKey && event.pressed) {
    const bool control = (event.mods & GLFW_MOD_CONTROL) != 0 || control_held_;
    if (control && event.key == GLFW_KEY_Z) return undo();
    if (control && event.key == GLFW_KEY_Y) return redo();
    if (control && event.key == GLFW_KEY_S) return saveProject();
    if (control && event.key == GLFW_KEY_E) return exportProject();
    if (control && event.key == GLFW_KEY_G) {
      groupSelected();
      return;
    }
    if (event.key == GLFW_KEY_DELETE) return deleteSelected();
    if (event.key == GLFW_KEY_ESCAPE) {
      if (cloud_ && cloud_->grow) cloud_->grow->cancel();
      drawing_.escape();
      measure_.escape();
      return;
    }
    if (!control) {
      switch (event.key) {
        case GLFW_KEY_N:
          return setTool(Tool::kNavigate);
        case GLFW_KEY_G:
          return setTool(Tool::kGrow);
        case GLFW_KEY_M:
          return setTool(Tool::kMeasure);
        case GLFW_KEY_P:
          return setTool(Tool::kPolygon);
        case GLFW_KEY_V:
          return setTool(Tool::kMove);
        case GLFW_KEY_E:
          if (!(cloud_ && cloud_->navigator->flying())) return setTool(Tool::kExtrude);
          break;
        case GLFW_KEY_R:
          scene_.registry().patch<ToolState>(scene_.toolEntity(),
                                             [](ToolState& t) { t.drawing.rectangle = !t.drawing.rectangle; });
          return;
        case GLFW_KEY_C:
          scene_.registry().patch<ToolState>(scene_.toolEntity(),
                                             [](ToolState& t) { t.drawing.copy = !t.drawing.copy; });
          return;
        case GLFW_KEY_K:
          return cornerOfSelected();
        case GLFW_KEY_X:
          return clipAtSelectedPlane();
        case GLFW_KEY_PAGE_UP:
        case GLFW_KEY_PAGE_DOWN:
          // The slice steps through the building by its thickness; without one, the slab along
          // its normal.
          if (clip_.slice) {
            clip_.slice_bottom_z += (event.key == GLFW_KEY_PAGE_UP ? 1.0 : -1.0) * clip_.slice_thickness;
            return;
          }
          if (clip_.slab) {
            clip_.slab->point +=
                (event.key == GLFW_KEY_PAGE_UP ? 1.0 : -1.0) * clip_.slab->thickness * clip_.slab->normal;
            return;
          }
          break;
        default:
          break;
      }
    }
  }
  if (!cloud_) return;
  if (clipBoxEvent(event)) return;
  // The navigator works in window pixels (a drag turns the view as far whatever the render scale,
  // which changes while the view moves); picks and the tools in render pixels (the window's, times
  // the render scale).
  const double scale = renderScale();
  const bool clicked =
      cloud_->navigator->handle(event, [this, scale](double x, double y) { return pickAt(x * scale, y * scale); });
  if (clicked) {
    const PointerView at = mousePointer(event.x * scale, event.y * scale);
    click(at);
    if (isDrawingTool(scene_.tool().active)) hovered_px_ = at.pixel;
  }
}

// The scene's overlay, with the clip box's edges and handles when there is one. Made anew only
// when the scene's overlay, the box or the lit handle changed.
bool Viewer::clipBoxEvent(const InputEvent& event) {
  if (!clip_.box) {
    box_drag_.reset();
    hovered_box_handle_.reset();
    return false;
  }
  const double scale = renderScale();
  const view::Camera& camera = cloud_->navigator->camera();
  const view::Ray ray = view::rayThroughPixel(camera, event.x * scale, event.y * scale);
  if (event.kind == InputEvent::Kind::kMouseMove) {
    if (box_drag_) {
      clip_.box = box_drag_->boxFor(ray);
      return true;
    }
    hovered_box_handle_ = boxHandleAt(*clip_.box, camera, event.x * scale, event.y * scale);
    return false;
  }
  if (event.kind != InputEvent::Kind::kMouseButton || event.button != GLFW_MOUSE_BUTTON_LEFT) return false;
  if (!event.pressed) {
    const bool dragging = box_drag_.has_value();
    box_drag_.reset();
    return dragging;
  }
  const std::optional<BoxHandle> handle = boxHandleAt(*clip_.box, camera, event.x * scale, event.y * scale);
  if (!handle) return false;
  box_drag_.emplace(*clip_.box, *handle, ray, (event.mods & GLFW_MOD_SHIFT) != 0 || shift_held_);
  return true;
}

}  // namespace plumb::viewer
