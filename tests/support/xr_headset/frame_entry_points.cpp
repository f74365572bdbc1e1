// Frame entry points of the simulated headset (OpenXR 1.0 specification, chapter 10 "Rendering":
// sections "Frame Waiting" and "Frame Submission", "Composition Layers"; chapter 12, section
// "XR_KHR_composition_layer_depth").
//
// xrWaitFrame never sleeps: each call is the script's next frame, predicted for display at
// (frame + 1) * the refresh period, so runs are deterministic and as fast as the application.
// It also plays the session states the frames cause (first frame: SYNCHRONIZED, VISIBLE, FOCUSED)
// and the script's events. A second xrWaitFrame without xrBeginFrame in between would block a real
// runtime for ever on a single thread; here it fails with XR_ERROR_CALL_ORDER_INVALID.
//
// xrEndFrame:
//   1. checks the frame end info and every layer (projection layers of two views, optional depth
//      info per view, quad layers) against the session's swapchains' released images;
//   2. appends the frame's line to frames.jsonl and, on captured frames, reads back the first
//      projection layer's views and every quad layer into PNGs (frame_output.h);
//   3. after the last frame of an "exit" script, steps the session to STOPPING.

#include <string>
#include <vector>

#include "tests/support/xr_headset/entry_points.h"
#include "tests/support/xr_headset/frame_output.h"
#include "tests/support/xr_headset/image_readback.h"
#include "tests/support/xr_headset/runtime_state.h"
#include "tests/support/xr_headset/space_poses.h"

namespace plumb::xr_headset {
namespace {

constexpr const char* kEndFrame = "xrEndFrame";

// A layer image to read back once the whole frame is checked.
struct PendingCapture {
  const Swapchain* swapchain = nullptr;
  std::uint32_t array_index = 0;
  XrRect2Di rect{};
  std::string file_name;
  std::string latest_name;  // an eye's latest-eye-E.png or latest-depth-E.pfm; empty for a quad
  bool depth = false;       // a depth image, read back to a Portable Float Map
};

XrResult checkSubImage(std::uint64_t session_id, const XrSwapchainSubImage& sub_image, bool want_depth,
                       const Swapchain*& swapchain) {
  swapchain = find(runtime().swapchains, idOf(sub_image.swapchain));
  if (swapchain == nullptr || swapchain->session != session_id) {
    return misuse(XR_ERROR_HANDLE_INVALID, kEndFrame, "a layer names an unknown XrSwapchain");
  }
  if (!swapchain->released) {
    return misuse(XR_ERROR_LAYER_INVALID, kEndFrame, "a layer's swapchain has no released image");
  }
  if (isDepthFormat(swapchain->spec.format) != want_depth) {
    return misuse(XR_ERROR_VALIDATION_FAILURE, kEndFrame,
                  want_depth ? "depth info needs a depth swapchain" : "a layer's colour needs a colour swapchain");
  }
  if (sub_image.imageArrayIndex >= swapchain->spec.array_size) {
    return misuse(XR_ERROR_VALIDATION_FAILURE, kEndFrame, "imageArrayIndex is past the swapchain's arraySize");
  }
  const XrRect2Di& rect = sub_image.imageRect;
  const bool inside = rect.offset.x >= 0 && rect.offset.y >= 0 && rect.extent.width > 0 && rect.extent.height > 0 &&
                      static_cast<std::int64_t>(rect.offset.x) + rect.extent.width <= swapchain->spec.width &&
                      static_cast<std::int64_t>(rect.offset.y) + rect.extent.height <= swapchain->spec.height;
  if (!inside) {
    return misuse(XR_ERROR_SWAPCHAIN_RECT_INVALID, kEndFrame,
                  "imageRect (" + std::to_string(rect.offset.x) + ", " + std::to_string(rect.offset.y) + ", " +
                      std::to_string(rect.extent.width) + " x " + std::to_string(rect.extent.height) +
                      ") is not inside the " + std::to_string(swapchain->spec.width) + " x " +
                      std::to_string(swapchain->spec.height) + " image");
  }
  return XR_SUCCESS;
}

XrResult checkLayerSpace(std::uint64_t session_id, XrSpace handle, const Space*& space) {
  space = find(runtime().spaces, idOf(handle));
  if (space == nullptr || space->session != session_id) {
    return misuse(XR_ERROR_HANDLE_INVALID, kEndFrame, "a layer names an unknown XrSpace");
  }
  return XR_SUCCESS;
}

XrResult checkDepthInfo(const Instance& instance, std::uint64_t session_id,
                        const XrCompositionLayerProjectionView& view, SubmittedView& recorded,
                        const Swapchain*& swapchain) {
  // Without the extension enabled, its structure is one the runtime does not know: ignored.
  const auto* depth = instance.depth_layers ? reinterpret_cast<const XrCompositionLayerDepthInfoKHR*>(
                                                  findInChain(view.next, XR_TYPE_COMPOSITION_LAYER_DEPTH_INFO_KHR))
                                            : nullptr;
  recorded.depth = depth != nullptr;
  if (depth == nullptr) return XR_SUCCESS;
  recorded.near_z = depth->nearZ;
  recorded.far_z = depth->farZ;
  if (const XrResult checked = checkSubImage(session_id, depth->subImage, true, swapchain); XR_FAILED(checked)) {
    return checked;
  }
  if (!(depth->minDepth >= 0 && depth->minDepth <= depth->maxDepth && depth->maxDepth <= 1)) {
    return misuse(XR_ERROR_VALIDATION_FAILURE, kEndFrame, "depth info needs 0 <= minDepth <= maxDepth <= 1");
  }
  if (depth->nearZ == depth->farZ)
    return misuse(XR_ERROR_VALIDATION_FAILURE, kEndFrame, "depth info's nearZ equals farZ");
  return XR_SUCCESS;
}

XrResult collectProjection(const Instance& instance, std::uint64_t session_id,
                           const XrCompositionLayerProjection& layer, XrTime display_time, bool first,
                           SubmittedFrame& submitted, std::vector<PendingCapture>& captures) {
  const Space* space = nullptr;
  if (const XrResult checked = checkLayerSpace(session_id, layer.space, space); XR_FAILED(checked)) return checked;
  if (layer.viewCount != 2 || layer.views == nullptr) {
    return misuse(XR_ERROR_VALIDATION_FAILURE, kEndFrame, "a projection layer needs the 2 views of primary stereo");
  }
  const std::optional<Pose> space_pose = locateInLocal(instance, *space, display_time);
  for (std::uint32_t eye = 0; eye < layer.viewCount; ++eye) {
    const XrCompositionLayerProjectionView& view = layer.views[eye];
    if (view.type != XR_TYPE_COMPOSITION_LAYER_PROJECTION_VIEW) {
      return misuse(XR_ERROR_VALIDATION_FAILURE, kEndFrame,
                    "views[] must have type XR_TYPE_COMPOSITION_LAYER_PROJECTION_VIEW");
    }
    if (!isValidPose(view.pose))
      return misuse(XR_ERROR_POSE_INVALID, kEndFrame, "a view's orientation is not a unit quaternion");
    const Swapchain* swapchain = nullptr;
    if (const XrResult checked = checkSubImage(session_id, view.subImage, false, swapchain); XR_FAILED(checked)) {
      return checked;
    }
    SubmittedView recorded;
    const Swapchain* depth_swapchain = nullptr;
    if (const XrResult checked = checkDepthInfo(instance, session_id, view, recorded, depth_swapchain);
        XR_FAILED(checked)) {
      return checked;
    }
    recorded.pose = space_pose ? compose(*space_pose, fromXr(view.pose)) : fromXr(view.pose);
    recorded.fov = view.fov;
    recorded.image_rect = view.subImage.imageRect;
    submitted.views.push_back(recorded);
    if (first)
      captures.push_back({swapchain, view.subImage.imageArrayIndex, view.subImage.imageRect,
                          eyeImageName(submitted.frame, eye), latestEyeImageName(eye), false});
    if (first && depth_swapchain != nullptr) {
      const auto* depth = reinterpret_cast<const XrCompositionLayerDepthInfoKHR*>(
          findInChain(view.next, XR_TYPE_COMPOSITION_LAYER_DEPTH_INFO_KHR));
      captures.push_back({depth_swapchain, depth->subImage.imageArrayIndex, depth->subImage.imageRect,
                          depthImageName(submitted.frame, eye), latestDepthImageName(eye), true});
    }
  }
  return XR_SUCCESS;
}

XrResult collectQuad(std::uint64_t session_id, const XrCompositionLayerQuad& layer, SubmittedFrame& submitted,
                     std::vector<PendingCapture>& captures) {
  const Space* space = nullptr;
  if (const XrResult checked = checkLayerSpace(session_id, layer.space, space); XR_FAILED(checked)) return checked;
  if (!isValidPose(layer.pose))
    return misuse(XR_ERROR_POSE_INVALID, kEndFrame, "a quad's orientation is not a unit quaternion");
  const Swapchain* swapchain = nullptr;
  if (const XrResult checked = checkSubImage(session_id, layer.subImage, false, swapchain); XR_FAILED(checked)) {
    return checked;
  }
  captures.push_back({swapchain, layer.subImage.imageArrayIndex, layer.subImage.imageRect,
                      quadImageName(submitted.frame, submitted.quad_count), "", false});
  ++submitted.quad_count;
  return XR_SUCCESS;
}

// Step 2: frames.jsonl, and the captured images.
XrResult writeFrame(const Instance& instance, Session& session, const SubmittedFrame& submitted,
                    const std::vector<PendingCapture>& captures) {
  if (instance.output_folder.empty()) return XR_SUCCESS;
  if (!appendFrameLine(instance.output_folder, frameJsonLine(submitted))) return XR_ERROR_RUNTIME_FAILURE;
  const bool captured = instance.script.captures(submitted.frame);
  for (const PendingCapture& capture : captures) {
    const bool latest = instance.script.capture_latest && !capture.latest_name.empty();
    if (!captured && !latest) continue;
    const VkImage image = capture.swapchain->images->images()[*capture.swapchain->released];
    const auto width = static_cast<std::uint32_t>(capture.rect.extent.width);
    const auto height = static_cast<std::uint32_t>(capture.rect.extent.height);
    if (capture.depth) {
      std::vector<float> depths;
      if (!readDepthImage(session.vulkan, *session.commands, image, capture.swapchain->spec.format, capture.array_index,
                          capture.rect, depths) ||
          (captured && !writePfm(instance.output_folder, capture.file_name, width, height, depths)) ||
          (latest && !writePfm(instance.output_folder, capture.latest_name, width, height, depths))) {
        return XR_ERROR_RUNTIME_FAILURE;
      }
      continue;
    }
    std::vector<std::uint8_t> rgba;
    if (!readColorImage(session.vulkan, *session.commands, image, capture.swapchain->spec.format, capture.array_index,
                        capture.rect, rgba)) {
      return XR_ERROR_RUNTIME_FAILURE;
    }
    if (captured && !writePng(instance.output_folder, capture.file_name, width, height, rgba)) {
      return XR_ERROR_RUNTIME_FAILURE;
    }
    if (latest && !writePng(instance.output_folder, capture.latest_name, width, height, rgba)) {
      return XR_ERROR_RUNTIME_FAILURE;
    }
  }
  return XR_SUCCESS;
}

}  // namespace

XrResult XRAPI_CALL xrWaitFrame(XrSession session, const XrFrameWaitInfo* wait_info, XrFrameState* frame_state) {
  constexpr const char* kSelf = "xrWaitFrame";
  std::lock_guard lock(runtime().mutex);
  Session* found = nullptr;
  Instance* owner = nullptr;
  if (const XrResult checked = lookUpSession(kSelf, session, found, owner); XR_FAILED(checked)) return checked;
  if (frame_state == nullptr || frame_state->type != XR_TYPE_FRAME_STATE ||
      (wait_info != nullptr && wait_info->type != XR_TYPE_FRAME_WAIT_INFO)) {
    return misuse(XR_ERROR_VALIDATION_FAILURE, kSelf,
                  "frameState must have type XR_TYPE_FRAME_STATE, frameWaitInfo null or XR_TYPE_FRAME_WAIT_INFO");
  }
  if (!found->running) return misuse(XR_ERROR_SESSION_NOT_RUNNING, kSelf, "the session is not running");
  if (found->loss_pending) {
    // The frame the loss was announced on has passed: the session is gone.
    found->lost = true;
    return misuse(XR_ERROR_SESSION_LOST, kSelf, "the session is lost (the script's \"lose\" event)");
  }
  if (found->frame_waited) {
    return misuse(XR_ERROR_CALL_ORDER_INVALID, kSelf,
                  "called again before xrBeginFrame (a real runtime would block here for ever)");
  }
  const std::uint64_t id = idOf(session);
  const auto frame = static_cast<std::uint64_t>(++found->waited_frame);
  found->frame_waited = true;
  if (!found->frames_started) {
    found->frames_started = true;
    if (found->state == XR_SESSION_STATE_READY) {
      changeState(*owner, id, *found, XR_SESSION_STATE_SYNCHRONIZED);
      changeState(*owner, id, *found, XR_SESSION_STATE_VISIBLE);
      changeState(*owner, id, *found, XR_SESSION_STATE_FOCUSED);
    }
  }
  const HeadsetScript& script = owner->script;
  switch (script.eventAt(frame)) {
    case ScriptEvent::kUnfocus:
      if (found->state == XR_SESSION_STATE_FOCUSED) {
        changeState(*owner, id, *found, XR_SESSION_STATE_VISIBLE);
      } else {
        report(kSelf, "the script's \"unfocus\" on frame " + std::to_string(frame) + " needs a focused session");
      }
      break;
    case ScriptEvent::kFocus:
      if (found->state == XR_SESSION_STATE_VISIBLE) {
        changeState(*owner, id, *found, XR_SESSION_STATE_FOCUSED);
      } else {
        report(kSelf, "the script's \"focus\" on frame " + std::to_string(frame) + " needs a visible session");
      }
      break;
    case ScriptEvent::kExit:
      stopSession(*owner, id, *found);
      break;
    case ScriptEvent::kLose:
      found->loss_pending = true;
      changeState(*owner, id, *found, XR_SESSION_STATE_LOSS_PENDING);
      break;
    case ScriptEvent::kNone:
      break;
  }
  // An application that skipped xrEndFrame still sees the script end.
  if (script.after_last_frame == AfterLastFrame::kExit && frame >= script.frameCount()) {
    stopSession(*owner, id, *found);
  }
  frame_state->predictedDisplayTime = displayTimeOf(script, static_cast<std::int64_t>(frame));
  frame_state->predictedDisplayPeriod = script.framePeriodNs();
  frame_state->shouldRender =
      found->state == XR_SESSION_STATE_VISIBLE || found->state == XR_SESSION_STATE_FOCUSED ? XR_TRUE : XR_FALSE;
  return sessionSuccess(*found);
}

XrResult XRAPI_CALL xrBeginFrame(XrSession session, const XrFrameBeginInfo* begin_info) {
  constexpr const char* kSelf = "xrBeginFrame";
  std::lock_guard lock(runtime().mutex);
  Session* found = nullptr;
  Instance* owner = nullptr;
  if (const XrResult checked = lookUpSession(kSelf, session, found, owner); XR_FAILED(checked)) return checked;
  if (begin_info != nullptr && begin_info->type != XR_TYPE_FRAME_BEGIN_INFO) {
    return misuse(XR_ERROR_VALIDATION_FAILURE, kSelf,
                  "frameBeginInfo must be null or of type XR_TYPE_FRAME_BEGIN_INFO");
  }
  if (!found->running) return misuse(XR_ERROR_SESSION_NOT_RUNNING, kSelf, "the session is not running");
  if (!found->frame_waited) return misuse(XR_ERROR_CALL_ORDER_INVALID, kSelf, "call xrWaitFrame first");
  const bool discarded = found->begun_frame.has_value();
  found->begun_frame = static_cast<std::uint64_t>(found->waited_frame);
  found->frame_waited = false;
  // A begun frame never ended is discarded: a success code, not a misuse.
  return discarded ? XR_FRAME_DISCARDED : sessionSuccess(*found);
}

XrResult XRAPI_CALL xrEndFrame(XrSession session, const XrFrameEndInfo* end_info) {
  std::lock_guard lock(runtime().mutex);
  Session* found = nullptr;
  Instance* owner = nullptr;
  if (const XrResult checked = lookUpSession(kEndFrame, session, found, owner); XR_FAILED(checked)) return checked;
  if (end_info == nullptr || end_info->type != XR_TYPE_FRAME_END_INFO) {
    return misuse(XR_ERROR_VALIDATION_FAILURE, kEndFrame, "frameEndInfo must have type XR_TYPE_FRAME_END_INFO");
  }
  if (!found->running) return misuse(XR_ERROR_SESSION_NOT_RUNNING, kEndFrame, "the session is not running");
  if (!found->begun_frame) return misuse(XR_ERROR_CALL_ORDER_INVALID, kEndFrame, "call xrBeginFrame first");
  if (end_info->displayTime <= 0) return misuse(XR_ERROR_TIME_INVALID, kEndFrame, "displayTime must be positive");
  if (end_info->environmentBlendMode != XR_ENVIRONMENT_BLEND_MODE_OPAQUE) {
    return misuse(XR_ERROR_ENVIRONMENT_BLEND_MODE_UNSUPPORTED, kEndFrame,
                  "only XR_ENVIRONMENT_BLEND_MODE_OPAQUE is offered");
  }
  if (end_info->layerCount > kMaxLayerCount) {
    return misuse(XR_ERROR_LAYER_LIMIT_EXCEEDED, kEndFrame, "more than " + std::to_string(kMaxLayerCount) + " layers");
  }
  if (end_info->layerCount > 0 && end_info->layers == nullptr)
    return misuse(XR_ERROR_LAYER_INVALID, kEndFrame, "null layers");

  // 1. The layers.
  const std::uint64_t id = idOf(session);
  SubmittedFrame submitted;
  submitted.frame = *found->begun_frame;
  submitted.display_time = end_info->displayTime;
  submitted.layer_count = end_info->layerCount;
  std::vector<PendingCapture> captures;
  bool first_projection = true;
  for (std::uint32_t i = 0; i < end_info->layerCount; ++i) {
    const XrCompositionLayerBaseHeader* layer = end_info->layers[i];
    if (layer == nullptr) return misuse(XR_ERROR_LAYER_INVALID, kEndFrame, "a null layer");
    XrResult checked = XR_SUCCESS;
    if (layer->type == XR_TYPE_COMPOSITION_LAYER_PROJECTION) {
      checked = collectProjection(*owner, id, *reinterpret_cast<const XrCompositionLayerProjection*>(layer),
                                  end_info->displayTime, first_projection, submitted, captures);
      first_projection = false;
    } else if (layer->type == XR_TYPE_COMPOSITION_LAYER_QUAD) {
      checked = collectQuad(id, *reinterpret_cast<const XrCompositionLayerQuad*>(layer), submitted, captures);
    } else {
      checked = misuse(XR_ERROR_LAYER_INVALID, kEndFrame, "only projection and quad layers are composited");
    }
    if (XR_FAILED(checked)) return checked;
  }
  found->begun_frame.reset();

  // 2. The output.
  if (const XrResult written = writeFrame(*owner, *found, submitted, captures); XR_FAILED(written)) return written;

  // 3. The script's end.
  const HeadsetScript& script = owner->script;
  if (script.after_last_frame == AfterLastFrame::kExit && submitted.frame + 1 >= script.frameCount()) {
    stopSession(*owner, id, *found);
  }
  return sessionSuccess(*found);
}

}  // namespace plumb::xr_headset
