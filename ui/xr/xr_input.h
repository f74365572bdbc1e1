#pragma once
// The controllers: one action set Plumb suggests bindings for on the common interaction
// profiles (Khronos simple, Oculus Touch, Valve Index), read once a frame. OpenXR 1.0
// specification, section 11 (input and haptics).
//
// What each input does is the viewer's business (ui/viewer/xr_frames.cpp); this only reads.
// Not thread-safe: the viewer's main thread owns it.

#include <openxr/openxr.h>

#include <Eigen/Core>
#include <array>

#include "ui/xr/stage.h"

namespace plumb::xr {

enum class Hand : std::size_t { kLeft = 0, kRight = 1 };

struct Controller {
  bool active = false;                                   // tracked and bound (the runtime has this hand)
  bool aim_valid = false;                                // the aim pose is known this frame
  Pose aim;                                              // in the stage
  float trigger = 0.0f;                                  // 0..1
  float squeeze = 0.0f;                                  // 0..1
  Eigen::Vector2f thumbstick = Eigen::Vector2f::Zero();  // x right, y forward, each -1..1
  bool primary = false;                                  // A or X (simple controller: menu)
  bool secondary = false;                                // B or Y
};

class Input {
 public:
  // Creates the actions and suggests bindings; attaches them to `session`. Throws xr::Error.
  Input(XrInstance instance, XrSession session);
  ~Input();
  Input(const Input&) = delete;
  Input& operator=(const Input&) = delete;

  // Reads every action at `time` (the frame's predicted display time), poses in `stage`. A
  // session not focused reads nothing: every controller inactive.
  void sync(XrSpace stage, XrTime time, bool focused);
  const Controller& controller(Hand hand) const { return controllers_[static_cast<std::size_t>(hand)]; }

 private:
  XrInstance instance_;
  XrSession session_;
  XrActionSet set_ = XR_NULL_HANDLE;
  XrAction aim_ = XR_NULL_HANDLE, trigger_ = XR_NULL_HANDLE, squeeze_ = XR_NULL_HANDLE, thumbstick_ = XR_NULL_HANDLE,
           primary_ = XR_NULL_HANDLE, secondary_ = XR_NULL_HANDLE;
  std::array<XrPath, 2> hands_{};
  std::array<XrSpace, 2> aim_spaces_{XR_NULL_HANDLE, XR_NULL_HANDLE};
  std::array<Controller, 2> controllers_{};
};

// An OpenXR pose as the stage's Pose.
Pose toPose(const XrPosef& pose);

}  // namespace plumb::xr
