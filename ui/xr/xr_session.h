#pragma once
// One OpenXR session on Plumb's Vulkan device: its life cycle, the stage space, a colour
// swapchain per eye and the frame loop. OpenXR 1.0 specification, sections 9 (session life
// cycle), 7 (spaces), 8 (view configurations), 10 (rendering: swapchains, xrWaitFrame,
// xrBeginFrame, xrEndFrame, projection layers) and 12.20 (XR_KHR_vulkan_enable2's binding and
// image layouts).
//
// The session begins when the runtime says it is ready and ends when it says it is stopping;
// the viewer polls it once a frame and, between beginFrame and endFrame, renders each eye into
// the image acquireEye gives it. Not thread-safe: the viewer's main thread owns it; the
// runtime may use the device's queue during these calls, which that thread also submits on.

#include <openxr/openxr.h>
#include <vulkan/vulkan.h>

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "engine/gpu/swapchain.h"
#include "engine/view/camera.h"
#include "ui/xr/hand_panel.h"
#include "ui/xr/stage.h"

namespace plumb::gpu {
class Device;
class Instance;
}  // namespace plumb::gpu

namespace plumb::xr {

class Input;
class Runtime;

// Where the session stands, for the viewer's messages.
enum class SessionState : std::uint8_t {
  kStarting,  // made, waiting for the runtime to be ready
  kRunning,   // frames flow (visible; focused gets input)
  kStopped,   // the runtime stopped it (the user took the headset off); it may become ready again
  kEnded,     // the runtime asked to exit, or the session was lost: destroy it
};

struct EyeView {
  Pose pose;  // in the stage
  view::EyeFov fov;
};

struct HeadsetFrame {
  XrTime display_time = 0;
  XrDuration display_period = 0;  // nanoseconds between frames: the headset's rate
  bool should_render = false;     // false: submit the frame empty (hidden, or tracking lost)
  std::array<EyeView, 2> eyes{};  // left, right
  Pose head;                      // the view space in the stage (between the eyes)
  // The eyes' near and far planes in the stage, metres, for the depth layer: set by whoever
  // renders the eyes (their projections' planes) before endFrame.
  double near_m = 0.05, far_m = 10'000.0;
};

class Session {
 public:
  static constexpr int kEyes = 2;

  // Throws xr::Error. `instance` and `device` must have been made through `runtime`
  // (gpu::VulkanFactory); all three outlive the session. The eyes' images are the runtime's
  // recommended size times `resolution_scale` (lavapipe cannot fill a headset's panels).
  Session(Runtime& runtime, const gpu::Instance& instance, const gpu::Device& device, double resolution_scale = 1.0);
  ~Session();
  Session(const Session&) = delete;
  Session& operator=(const Session&) = delete;

  // Handles the runtime's events: begins and ends the session as it asks. Returns the state
  // now and, through `messages`, each change in words, oldest first (none when nothing changed).
  SessionState poll(std::vector<std::string>& messages);
  SessionState state() const { return state_; }
  bool focused() const { return focused_; }

  // xrWaitFrame (which paces the loop to the headset), xrBeginFrame and the views; nothing
  // unless running. Then exactly one endFrame.
  std::optional<HeadsetFrame> beginFrame();
  // The eye's next swapchain image, waited for: render into it, hand it back in
  // COLOR_ATTACHMENT_OPTIMAL, then releaseEye. With a depth image too where the runtime takes
  // depth (XR_KHR_composition_layer_depth): write the eye's depth into it (DEPTH_STENCIL_
  // ATTACHMENT_OPTIMAL). Only between beginFrame and endFrame.
  gpu::SwapchainImage acquireEye(int eye);
  void releaseEye(int eye);
  // Submits the frame: a projection layer of the eyes as `frame` located them when
  // `rendered`, else no layer; over it the panel at `panel` when given (its image released
  // this frame).
  void endFrame(const HeadsetFrame& frame, bool rendered, const HandPanel* panel = nullptr);

  // The panel's swapchain (the palette in the hand): `extent` pixels of `format`, which must
  // be one the runtime offers (else false, and no panel). Made again when the extent changes.
  bool preparePanel(VkExtent2D extent, VkFormat format);
  // Its next image, waited for (COLOR_ATTACHMENT_OPTIMAL, as the eyes'), and back.
  gpu::SwapchainImage acquirePanel();
  void releasePanel();

  VkExtent2D eyeExtent() const { return extent_; }
  Input& input() { return *input_; }
  XrSpace stage() const { return stage_; }
  // Asks the runtime to end the session (the user left VR); it stops, then ends.
  void requestExit();

 private:
  struct Swapchain {
    XrSwapchain handle = XR_NULL_HANDLE;
    std::vector<VkImage> images;
    std::uint32_t acquired = 0;
  };

  void destroy();
  Swapchain createSwapchain(VkExtent2D extent, VkFormat format,
                            XrSwapchainUsageFlags usage = XR_SWAPCHAIN_USAGE_COLOR_ATTACHMENT_BIT |
                                                          XR_SWAPCHAIN_USAGE_TRANSFER_DST_BIT) const;
  gpu::SwapchainImage acquire(Swapchain& swapchain, VkExtent2D extent, VkFormat format);

  Runtime& runtime_;
  XrSession session_ = XR_NULL_HANDLE;
  XrSpace stage_ = XR_NULL_HANDLE;
  XrSpace view_space_ = XR_NULL_HANDLE;
  std::array<Swapchain, kEyes> swapchains_{};
  std::array<Swapchain, kEyes> depth_swapchains_{};  // none where the runtime takes no depth
  VkFormat depth_format_ = VK_FORMAT_UNDEFINED;
  Swapchain panel_;
  VkExtent2D panel_extent_{0, 0};
  VkFormat panel_format_ = VK_FORMAT_UNDEFINED;
  std::vector<std::int64_t> formats_;  // what the runtime offers, its preference first
  VkExtent2D extent_{0, 0};
  VkFormat format_ = VK_FORMAT_UNDEFINED;
  std::unique_ptr<Input> input_;
  SessionState state_ = SessionState::kStarting;
  bool focused_ = false;
  bool exit_requested_ = false;
};

}  // namespace plumb::xr
