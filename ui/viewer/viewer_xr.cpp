// The viewer in a headset (plumb view --xr): the session's life, a frame per headset frame,
// the controllers as another input source of the same tools.
//
//   frame: poll the session (begin, stop, end as the runtime says) -> xrWaitFrame and the eyes'
//          views -> the controllers (the trigger grows where the right hand points) -> the
//          right eye, then the left eye presented to its image and to the window (the mirror)
//          -> xrEndFrame
//
// The headset renders through the window's renderer and settings: one cloud, one colour mode,
// one section; each eye is a camera of its own (an off-axis frustum from xrLocateViews).

#include <imgui.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>

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
// The pick view along a controller's ray: a narrow frustum (2 degrees each side vertically)
// whose centre pixel is the ray.
constexpr double kPickHalfAngleRad = 0.035;

}  // namespace

std::unique_ptr<xr::Runtime> Viewer::connectHeadset(const ViewerOptions&) {
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
  std::string message;
  try {
    const xr::SessionState state = xr_session_->poll(message);
    if (!message.empty()) {
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
  if (!xr_session_ || !cloud_) return false;
  std::optional<xr::HeadsetFrame> frame;
  try {
    frame = xr_session_->beginFrame();
    if (!frame) return false;  // not running (starting, stopped): the desktop as usual
    ++xr_frames_;
    bool rendered = false;
    bool window_presented = false;
    if (frame->should_render) {
      if (!xr_stage_) xr_stage_ = xr::placementAt(cloud_->navigator->camera(), frame->head);
      headsetControllers(*frame);
      render::RenderSettings eye_settings = settings_;
      eye_settings.clip = clip_.region();
      cloud_->renderer->setOverlay(withClipBox(overlay_.update(scene_.registry())));
      const VkExtent2D extent = xr_session_->eyeExtent();
      const auto eyeCamera = [&](int eye) {
        const xr::EyeView& view = frame->eyes[static_cast<std::size_t>(eye)];
        return xr::eyeCamera(*xr_stage_, view.pose, view.fov, static_cast<int>(extent.width),
                             static_cast<int>(extent.height));
      };
      // The right eye alone, then the left one into its image and the window's.
      const gpu::SwapchainImage right = xr_session_->acquireEye(1);
      cloud_->renderer->render(eyeCamera(1), eye_settings, render::NodeLoading::kStream, {&right, 1});
      xr_session_->releaseEye(1);
      const gpu::SwapchainImage left = xr_session_->acquireEye(0);
      const std::optional<gpu::SwapchainImage> window = swapchain_.acquire();
      std::array<gpu::SwapchainImage, 2> images{left, {}};
      if (window) images[1] = *window;
      pending_screenshot_ = window && screenshot && swapchain_.readable();
      last_stats_ = cloud_->renderer->render(eyeCamera(0), eye_settings, render::NodeLoading::kStream,
                                             {images.data(), window ? 2u : 1u});
      xr_session_->releaseEye(0);
      if (window) {
        swapchain_.present(*window);
        window_presented = true;
      }
      rendered = true;
    }
    xr_session_->endFrame(*frame, rendered);
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

// The right controller's trigger, pulled, grows where its ray meets the cloud: the point comes
// from the visibility buffer of a narrow view along the ray, as the mouse's from the window's.
void Viewer::headsetControllers(const xr::HeadsetFrame& frame) {
  const xr::Controller& right = xr_session_->input().controller(xr::Hand::kRight);
  const bool pulled = right.active && right.aim_valid && right.trigger >= kTriggerPressed;
  const bool released = !right.active || right.trigger <= kTriggerReleased;
  const bool fire = pulled && !xr_trigger_held_;
  if (pulled) xr_trigger_held_ = true;
  if (released) xr_trigger_held_ = false;
  if (!fire || scene_.tool().active != Tool::kGrow) return;

  const VkExtent2D extent = xr_session_->eyeExtent();
  const double aspect = static_cast<double>(extent.width) / extent.height;
  const double vertical = std::tan(kPickHalfAngleRad), horizontal = vertical * aspect;
  view::Camera along = xr::eyeCamera(
      *xr_stage_, right.aim, {-std::atan(horizontal), std::atan(horizontal), kPickHalfAngleRad, -kPickHalfAngleRad},
      static_cast<int>(extent.width), static_cast<int>(extent.height));
  render::RenderSettings pick_settings = settings_;
  pick_settings.clip = clip_.region();
  cloud_->renderer->render(along, pick_settings, render::NodeLoading::kWait);
  const std::optional<render::PickedPoint> picked =
      cloud_->renderer->pick(static_cast<int>(extent.width / 2), static_cast<int>(extent.height / 2), 4);
  if (!picked) {
    xr_message_ = "the controller points at nothing";
    return;
  }
  const Eigen::Vector3d point(picked->position[0], picked->position[1], picked->position[2]);
  // The detail of the eye that sees it, at the headset's full resolution.
  const xr::EyeView& eye = frame.eyes[0];
  const double full = 1.0 / xr_resolution_scale_;
  const view::Camera eye_camera =
      xr::eyeCamera(*xr_stage_, eye.pose, eye.fov, static_cast<int>(extent.width), static_cast<int>(extent.height));
  std::printf("plumb view: the controller grows at (%.3f, %.3f, %.3f)\n", point.x(), point.y(), point.z());
  startGrow(point, {eye_camera, extent.width * full, extent.height * full});
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
