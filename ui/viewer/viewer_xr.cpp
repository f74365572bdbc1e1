// The viewer in a headset (plumb view --xr): the session's life, a frame per headset frame,
// the controllers as another input source of the same tools.
//
//   frame: poll the session (begin, stop, end as the runtime says) -> xrWaitFrame and the eyes'
//          views -> moving (sticks, grips, B/Y) -> the palette's panel above the left hand and
//          the right controller on it, or in the scene (hover, trigger: the tools' clicks) ->
//          the right eye, then the left eye presented to its image and to the window (the
//          mirror), each with its depth -> the panel's image -> xrEndFrame
//
// The headset renders through the window's renderer and settings: one cloud, one colour mode,
// one section; each eye is a camera of its own (an off-axis frustum from xrLocateViews).

#include <imgui.h>

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "engine/gpu/commands.h"
#include "engine/render/point_renderer.h"
#include "ui/viewer/imgui_layer.h"
#include "ui/viewer/viewer.h"
#include "ui/xr/xr_check.h"
#include "ui/xr/xr_input.h"
#include "ui/xr/xr_runtime.h"
#include "ui/xr/xr_session.h"

namespace plumb::viewer {
namespace {

constexpr float kTriggerPressed = 0.75f, kTriggerReleased = 0.25f;  // hysteresis: one pull, one grow
constexpr double kWalkSpeed = 1.5;                                  // stage metres a second, stick full
constexpr double kSnapTurnRad = M_PI / 6.0;                         // 30 degrees a push
constexpr double kStickDeadZone = 0.15;
constexpr double kLeastBudgetShare = 0.1;  // of the point budget, the eyes' least
// The view along a controller's ray: 20 degrees each side vertically, so that the snapping
// radius (a dozen pixels) is about 1.3 degrees of a hand's aim at the eyes' resolution.
constexpr double kPointerHalfAngleRad = 0.35;

}  // namespace

std::unique_ptr<xr::Runtime> Viewer::connectHeadset() {
  // The loader prints its own lines for a missing runtime; the one message below says it all
  // (XR_LOADER_DEBUG=error brings the loader's back).
  setenv("XR_LOADER_DEBUG", "none", 0);
  try {
    auto runtime = std::make_unique<xr::Runtime>();
    std::printf("plumb view: headset: %s\n", runtime->name().c_str());
    return runtime;
  } catch (const xr::Error& error) {
    std::fprintf(stderr, "plumb view: no headset: %s; going on on the desktop\n", error.what());
    return nullptr;
  }
}

void Viewer::startHeadsetSession() {
  if (!xr_runtime_ || xr_session_) return;
  try {
    xr_session_ = std::make_unique<xr::Session>(*xr_runtime_, instance_, device_, xr_resolution_scale_);
    xr_stage_.reset();  // placed where the desktop camera is at the first frame
    xr_message_ = "headset session starting";
    std::printf("plumb view: headset session on %s, %u x %u pixels an eye\n", xr_runtime_->name().c_str(),
                xr_session_->eyeExtent().width, xr_session_->eyeExtent().height);
  } catch (const xr::Error& error) {
    xr_message_ = error.what();
    std::fprintf(stderr, "plumb view: no headset session: %s; going on on the desktop\n", error.what());
  }
}

void Viewer::pollHeadset() {
  if (!xr_session_) return;
  std::vector<std::string> messages;
  try {
    const xr::SessionState state = xr_session_->poll(messages);
    for (const std::string& message : messages) {
      xr_message_ = message;
      std::printf("plumb view: %s\n", message.c_str());
    }
    if (state == xr::SessionState::kEnded) {
      vkDeviceWaitIdle(device_.handle());  // the eyes' last frames used its images
      xr_session_.reset();
      xr_trigger_held_ = false;
      std::printf("plumb view: the headset session ended; the desktop goes on\n");
    }
  } catch (const xr::Error& error) {
    xr_message_ = error.what();
    std::fprintf(stderr, "plumb view: the headset session failed: %s; going on on the desktop\n", error.what());
    vkDeviceWaitIdle(device_.handle());
    xr_session_.reset();
  }
}

bool Viewer::renderHeadsetFrame(bool screenshot, const std::string& screenshot_name) {
  if (!xr_session_) return false;
  std::optional<xr::HeadsetFrame> frame;
  try {
    frame = xr_session_->beginFrame();
    if (!frame) return false;  // not running (starting, stopped): the desktop as usual
    if (!cloud_) {
      // Still loading: empty frames keep the runtime's pacing (it shows its own waiting view),
      // the window shows the progress.
      xr_session_->endFrame(*frame, false);
      return false;
    }
    ++xr_frames_;
    bool rendered = false;
    bool window_presented = false;
    if (frame->should_render) {
      if (!xr_stage_) xr_stage_ = xr::placementAt(cloud_->navigator->camera(), frame->head);
      moveInHeadset(*frame);
      // The eyes' cameras where this frame's moves left the stage.
      const VkExtent2D extent = xr_session_->eyeExtent();
      std::array<view::Camera, 2> eyes;
      for (std::size_t eye = 0; eye < 2; ++eye) {
        eyes[eye] = xr::eyeCamera(*xr_stage_, frame->eyes[eye].pose, frame->eyes[eye].fov,
                                  static_cast<int>(extent.width), static_cast<int>(extent.height));
      }
      placeHeadsetPanel();
      if (!pointAtHeadsetPanel()) headsetControllers(eyes[0]);
      adaptHeadsetBudget(*frame);
      render::RenderSettings eye_settings = settings_;
      eye_settings.clip = clip_.region();
      eye_settings.selection.point_budget = headsetBudget();
      cloud_->renderer->setOverlay(withClipBox(overlay_.update(scene_.registry())));
      const view::Camera both = xr::bothEyesCamera(eyes[0], eyes[1]);  // one selection, the same detail in each eye
      frame->near_m = eyes[0].near_m / xr_stage_->scale;               // the depth layer's planes, in the stage
      frame->far_m = eyes[0].far_m / xr_stage_->scale;
      const auto timeEye = [&] {
        if (!options_.profile) return;
        if (const std::optional<render::GpuTimings> timings = cloud_->renderer->gpuTimings()) {
          xr_eye_gpu_ms_.push_back(timings->splat_ms + timings->resolve_ms);
        }
      };
      // The right eye alone, then the left one into its image and the window's.
      const gpu::SwapchainImage right = xr_session_->acquireEye(1);
      cloud_->renderer->render(eyes[1], eye_settings, render::NodeLoading::kStream, {&right, 1}, &both);
      xr_session_->releaseEye(1);
      timeEye();
      const gpu::SwapchainImage left = xr_session_->acquireEye(0);
      const std::optional<gpu::SwapchainImage> window = swapchain_.acquire();
      std::array<gpu::SwapchainImage, 2> images{left, {}};
      if (window) images[1] = *window;
      pending_screenshot_ = window && screenshot && swapchain_.readable();
      last_stats_ = cloud_->renderer->render(eyes[0], eye_settings, render::NodeLoading::kStream,
                                             {images.data(), window ? 2u : 1u}, &both);
      xr_session_->releaseEye(0);
      timeEye();
      if (window) {
        swapchain_.present(*window);
        window_presented = true;
      }
      rendered = true;
    }
    if (rendered && xr_panel_) drawHeadsetPanel();
    xr_session_->endFrame(*frame, rendered, rendered && xr_panel_ ? &*xr_panel_ : nullptr);
    if (screenshot) {
      if (!pending_screenshot_) {
        std::fprintf(stderr, "plumb view: no screenshot of this headset frame (not rendered or not readable)\n");
        exit_status_ = 1;
      } else {
        cloud_->renderer->waitForFrames();
        writeScreenshot(screenshot_name);
      }
      pending_screenshot_ = false;
    }
    if (!window_presented) presentInterfaceOnly();
    return true;
  } catch (const xr::Error& error) {
    xr_message_ = error.what();
    std::fprintf(stderr, "plumb view: the headset frame failed: %s; going on on the desktop\n", error.what());
    vkDeviceWaitIdle(device_.handle());
    xr_session_.reset();
    return false;
  }
}

// Moving in the building: the left thumbstick walks where the head faces, the right one turns
// by steps; a squeeze holds the world (one hand moves and turns it, two also scale it: the
// model in the hands); B or Y sets the model on a table in front of the user, or back to 1:1
// where the desktop's view is. Times come from the headset's frame period, so a scripted
// session moves the same whatever the machine's speed.
void Viewer::moveInHeadset(const xr::HeadsetFrame& frame) {
  const xr::Input& input = xr_session_->input();
  const xr::Controller& left = input.controller(xr::Hand::kLeft);
  const xr::Controller& right = input.controller(xr::Hand::kRight);
  const double period_s = static_cast<double>(frame.display_period) * 1e-9;

  const bool secondary = (left.active && left.secondary) || (right.active && right.secondary);
  if (secondary && !xr_secondary_held_) {
    xr_model_ = !xr_model_;
    if (xr_model_) {
      const lod::Box3& box = cloud_->framing;
      const Eigen::Vector3d forward = frame.head.orientation * Eigen::Vector3d(0.0, 0.0, -1.0);
      const Eigen::Vector3d level = Eigen::Vector3d(forward.x(), 0.0, forward.z()).normalized();
      const Eigen::Vector3d table = frame.head.position + 0.5 * level - Eigen::Vector3d(0.0, 0.5, 0.0);
      xr_stage_ = xr::modelOnTable(*xr_stage_, {box.min[0], box.min[1], box.min[2]},
                                   {box.max[0], box.max[1], box.max[2]}, table);
    } else {
      xr_stage_ = xr::placementAt(cloud_->navigator->camera(), frame.head);
    }
    xr_grab_.reset();
    xr_message_ = xr_model_ ? "the model on a table (B or Y: back to 1:1)" : "1:1";
  }
  xr_secondary_held_ = secondary;

  // Squeezing hands hold the world; a hand joining or leaving starts the hold anew from here.
  const auto squeezing = [](const xr::Controller& c) {
    return c.active && c.aim_valid && c.squeeze >= kTriggerPressed;
  };
  const int hands = (squeezing(left) ? 1 : 0) | (squeezing(right) ? 2 : 0);
  if (hands == 0) {
    xr_grab_.reset();
  } else {
    const xr::Hold hold = hands == 3   ? xr::holdOf(left.aim, right.aim)
                          : hands == 1 ? xr::holdOf(left.aim)
                                       : xr::holdOf(right.aim);
    if (!xr_grab_ || xr_grab_->hands != hands) xr_grab_ = HeadsetGrab{hands, *xr_stage_, hold};
    xr_stage_ = xr::dragged(xr_grab_->start, xr_grab_->from, hold);
    return;  // held: the sticks wait
  }

  if (left.active && left.thumbstick.norm() > kStickDeadZone) {
    const Eigen::Vector3d forward = frame.head.orientation * Eigen::Vector3d(0.0, 0.0, -1.0);
    const Eigen::Vector3d ahead = Eigen::Vector3d(forward.x(), 0.0, forward.z()).normalized();
    const Eigen::Vector3d aside(-ahead.z(), 0.0, ahead.x());  // to the right of ahead
    const Eigen::Vector3d step =
        kWalkSpeed * period_s * (ahead * double{left.thumbstick.y()} + aside * double{left.thumbstick.x()});
    xr_stage_ = xr::walked(*xr_stage_, step);
  }
  const float turn = right.active ? right.thumbstick.x() : 0.0f;
  if (std::abs(turn) > 0.7f && !xr_turn_held_) {
    xr_stage_ = xr::turned(*xr_stage_, frame.head.position, turn > 0.0f ? -kSnapTurnRad : kSnapTurnRad);
  }
  if (std::abs(turn) > 0.7f) xr_turn_held_ = true;
  if (std::abs(turn) < 0.3f) xr_turn_held_ = false;
}

// The palette on a panel above the left hand, the window's size in pixels, while that hand is
// tracked and the runtime takes the window's format for it.
void Viewer::placeHeadsetPanel() {
  xr_panel_.reset();
  const xr::Controller& left = xr_session_->input().controller(xr::Hand::kLeft);
  const VkExtent2D size = window_.framebufferSize();
  if (!left.active || !left.aim_valid || size.width == 0 || size.height == 0) return;
  if (!xr_session_->preparePanel(size, swapchain_.format())) {
    if (!xr_panel_unavailable_said_) {
      std::fprintf(stderr,
                   "plumb view: the headset's runtime takes no image of the window's format: no palette in "
                   "the hand (the window's palette still works)\n");
      xr_panel_unavailable_said_ = true;
    }
    return;
  }
  xr_panel_ = xr::panelOnHand(left.aim, static_cast<double>(size.width) / size.height);
}

// Where the right controller's ray meets the panel, it is the mouse there: its trigger the
// left button. True while it points at the panel (the scene then takes no pointer).
bool Viewer::pointAtHeadsetPanel() {
  const xr::Controller& right = xr_session_->input().controller(xr::Hand::kRight);
  const std::optional<Eigen::Vector2d> uv =
      xr_panel_ && right.active && right.aim_valid ? xr::panelPoint(*xr_panel_, right.aim) : std::nullopt;
  const auto mouse = [](InputEvent::Kind kind, const Eigen::Vector2d& at, bool pressed = false) {
    return InputEvent{.kind = kind, .x = at.x(), .y = at.y(), .button = GLFW_MOUSE_BUTTON_LEFT, .pressed = pressed};
  };
  if (!uv) {
    if (xr_panel_pressed_) xr_panel_events_.push_back(mouse(InputEvent::Kind::kMouseButton, {-1.0, -1.0}, false));
    xr_panel_pressed_ = false;
    return false;
  }
  const VkExtent2D size = window_.framebufferSize();
  const Eigen::Vector2d at(uv->x() * size.width, uv->y() * size.height);
  xr_panel_events_.push_back(mouse(InputEvent::Kind::kMouseMove, at));
  const bool pressed = right.trigger >= (xr_panel_pressed_ ? kTriggerReleased : kTriggerPressed);
  if (pressed != xr_panel_pressed_) xr_panel_events_.push_back(mouse(InputEvent::Kind::kMouseButton, at, pressed));
  xr_panel_pressed_ = pressed;
  xr_trigger_held_ = pressed;  // a pull that began on the panel does not click the scene as it leaves
  xr_aim_point_.reset();
  return true;
}

// The palette drawn onto the panel's image: cleared transparent, so that the scene shows
// between the palette's windows.
void Viewer::drawHeadsetPanel() {
  const gpu::SwapchainImage image = xr_session_->acquirePanel();
  if (ui_frames_ >= 1) ui_timeline_.wait(ui_frames_, UINT64_MAX);
  ui_commands_.reset();
  VkCommandBuffer commands = ui_commands_.begin();
  gpu::imageBarrier(commands, image.image, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                    VK_PIPELINE_STAGE_2_CLEAR_BIT, VK_ACCESS_2_NONE, VK_PIPELINE_STAGE_2_CLEAR_BIT,
                    VK_ACCESS_2_TRANSFER_WRITE_BIT);
  const VkClearColorValue clear{{0.0f, 0.0f, 0.0f, 0.0f}};
  const VkImageSubresourceRange range{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
  vkCmdClearColorImage(commands, image.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &clear, 1, &range);
  imgui_.record(commands, image);
  gpu::submit(device_, commands, ui_timeline_, ++ui_frames_);
  xr_session_->releasePanel();
}

// The right controller is a pointer as the mouse is: a view along its ray, whose centre pixel
// it points with, wide enough that the snapping radius in pixels is a comfortable angle for a
// hand. Its movement is the last aim point's shift in that view. Picking renders that view
// first, then reads its visibility buffer as a mouse click reads the window's.
std::optional<PointerView> Viewer::controllerPointer(const view::Camera& left_eye) {
  const xr::Controller& right = xr_session_->input().controller(xr::Hand::kRight);
  if (!right.active || !right.aim_valid) {
    xr_aim_point_.reset();
    return std::nullopt;
  }
  const VkExtent2D extent = xr_session_->eyeExtent();
  const double aspect = static_cast<double>(extent.width) / extent.height;
  const double vertical = std::tan(kPointerHalfAngleRad), horizontal = vertical * aspect;
  PointerView at;
  at.camera =
      xr::eyeCamera(*xr_stage_, right.aim,
                    {-std::atan(horizontal), std::atan(horizontal), kPointerHalfAngleRad, -kPointerHalfAngleRad},
                    static_cast<int>(extent.width), static_cast<int>(extent.height));
  at.pixel = Eigen::Vector2d(0.5 * extent.width, 0.5 * extent.height);
  if (xr_aim_point_) {
    if (const std::optional<Eigen::Vector2d> before = view::pixelOf(at.camera, *xr_aim_point_)) {
      at.motion_px = at.pixel - *before;
    }
  }
  at.pick = [this, camera = at.camera](double x, double y) -> std::optional<Eigen::Vector3d> {
    render::RenderSettings pick_settings = settings_;
    pick_settings.clip = clip_.region();
    last_stats_ = cloud_->renderer->render(camera, pick_settings, render::NodeLoading::kWait);
    return pickAt(x, y);
  };
  // A grow's detail: the left eye's, at the headset's full resolution.
  const double full = 1.0 / xr_resolution_scale_;
  at.click_view = {left_eye, extent.width * full, extent.height * full};
  return at;
}

// The right controller: its hover snaps and finds directions every frame; A held locks the
// direction; its trigger, pulled, clicks (grows, picks a measurement's term, places a vertex,
// selects).
void Viewer::headsetControllers(const view::Camera& left_eye) {
  const std::optional<PointerView> at = controllerPointer(left_eye);
  const xr::Controller& right = xr_session_->input().controller(xr::Hand::kRight);
  const bool pulled = at && right.trigger >= kTriggerPressed;
  const bool fire = pulled && !xr_trigger_held_;
  if (pulled) xr_trigger_held_ = true;
  if (!at || right.trigger <= kTriggerReleased) xr_trigger_held_ = false;
  if (!at) return;

  // A held locks the drawing tools' direction, as Shift does on the desktop.
  if (right.primary != xr_lock_held_) {
    xr_lock_held_ = right.primary;
    drawing_.lockDirection(right.primary);
  }
  hoverAt(at);
  const std::optional<Snap>& hover = scene_.tool().hover;
  const view::Ray ray = view::rayThroughPixel(at->camera, at->pixel.x(), at->pixel.y());
  xr_aim_point_ = hover ? hover->position : ray.origin + 2.0 * xr_stage_->scale * ray.direction;
  if (!fire) return;
  if (scene_.tool().active == Tool::kGrow) {
    const std::optional<Eigen::Vector3d> picked = at->pick(at->pixel.x(), at->pixel.y());
    if (!picked) {
      xr_message_ = "the controller points at nothing";
      return;
    }
    startGrow(*picked, at->click_view);
    if (grow_panel_.last) {
      std::printf("plumb view: the controller grows at (%.3f, %.3f, %.3f), a pixel %.2f mm there\n", picked->x(),
                  picked->y(), picked->z(), grow_panel_.last->pixel_size_m * 1e3);
    }
    return;
  }
  click(*at);
}

// The eyes' point budget follows the frame time towards the headset's period, as a moving
// desktop view's does towards 30 frames a second; on a script's clock, or with
// --fixed-quality, it keeps the whole budget.
void Viewer::adaptHeadsetBudget(const xr::HeadsetFrame& frame) {
  const Clock::time_point now = Clock::now();
  const bool timed = xr_last_frame_ != Clock::time_point{};
  const double frame_ms = std::chrono::duration<double, std::milli>(now - xr_last_frame_).count();
  xr_last_frame_ = now;
  if (!timed) return;
  xr_frame_ms_.push_back(frame_ms);
  if ((script_ && !options_.script_wall_clock) || !adaptive_quality_) return;
  const double period_ms = static_cast<double>(frame.display_period) * 1e-6;
  if (period_ms <= 0.0) return;
  const double step = std::clamp(std::sqrt(period_ms / std::max(frame_ms, 1.0)), 0.8, 1.25);
  // Never below a tenth: on lavapipe a frame's fixed costs (the mirror, the palette, the
  // presentation) alone exceed a headset's period, and fewer points would not buy it back.
  xr_budget_share_ = std::clamp(xr_budget_share_ * step, kLeastBudgetShare, 1.0);
}

std::uint64_t Viewer::headsetBudget() const {
  return static_cast<std::uint64_t>(static_cast<double>(settings_.selection.point_budget) * xr_budget_share_);
}

void Viewer::reportHeadset() const {
  if (xr_frame_ms_.empty()) return;
  const auto median = [](std::vector<double> values) {
    std::sort(values.begin(), values.end());
    return values[values.size() / 2];
  };
  const double frame_ms = median(xr_frame_ms_);
  const auto budget = static_cast<unsigned long long>(headsetBudget());
  std::printf(
      "plumb view: headset: %zu frames, median %.1f ms a frame (%.1f Hz; both eyes and the mirror), budget "
      "%llu points at the end, %s\n",
      xr_frame_ms_.size(), frame_ms, 1e3 / frame_ms, budget, device_.name().c_str());
  if (!xr_eye_gpu_ms_.empty()) {
    std::printf("plumb view: headset: GPU time an eye %.1f ms (median of %zu, splat and resolve)\n",
                median(xr_eye_gpu_ms_), xr_eye_gpu_ms_.size());
  }
}

void Viewer::drawHeadsetControls() {
  if (!xr_runtime_) {
    ImGui::TextDisabled("VR: start with --xr (plumb view --xr)");
    return;
  }
  if (xr_session_) {
    if (ImGui::Button("Leave VR")) {
      try {
        xr_session_->requestExit();
      } catch (const xr::Error& error) {
        xr_message_ = error.what();
      }
    }
  } else if (ImGui::Button("Enter VR")) {
    startHeadsetSession();
  }
  ImGui::SameLine();
  ImGui::TextDisabled("%s", xr_message_.c_str());
}

}  // namespace plumb::viewer
