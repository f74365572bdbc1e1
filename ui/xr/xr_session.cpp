// The session's life cycle and frames.
//
//   1. xrCreateSession with the Vulkan binding (XrGraphicsBindingVulkan2KHR: Plumb's instance,
//      physical device, device and its one queue); the stage space (STAGE where the runtime
//      has one: the floor at 0, else LOCAL); the controllers' actions.
//   2. A colour swapchain per eye at the recommended size: R8G8B8A8_SRGB where offered, so
//      that the renderer's bytes (already sRGB-encoded, as the window shows them) are copied
//      unchanged and the compositor decodes them as it should.
//   3. Events: READY -> xrBeginSession, STOPPING -> xrEndSession, EXITING and LOSS_PENDING ->
//      ended; FOCUSED and VISIBLE say whether input and pictures reach the user.
//   4. Frames: xrWaitFrame, xrBeginFrame, xrLocateViews; each eye acquired, rendered,
//      released; xrEndFrame with one projection layer of the views located for this frame.

#include "ui/xr/xr_session.h"

#define XR_USE_GRAPHICS_API_VULKAN
#include <openxr/openxr_platform.h>

#include <algorithm>
#include <cmath>

#include "engine/gpu/device.h"
#include "engine/gpu/instance.h"
#include "ui/xr/xr_check.h"
#include "ui/xr/xr_input.h"
#include "ui/xr/xr_runtime.h"

namespace plumb::xr {
namespace {

constexpr XrViewConfigurationType kStereo = XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO;

XrSpace referenceSpace(XrSession session, XrReferenceSpaceType type) {
  auto create = xrStruct<XrReferenceSpaceCreateInfo>(XR_TYPE_REFERENCE_SPACE_CREATE_INFO);
  create.referenceSpaceType = type;
  create.poseInReferenceSpace.orientation.w = 1.0f;
  XrSpace space = XR_NULL_HANDLE;
  check(xrCreateReferenceSpace(session, &create, &space), "xrCreateReferenceSpace");
  return space;
}

XrReferenceSpaceType stageType(XrSession session) {
  std::uint32_t count = 0;
  check(xrEnumerateReferenceSpaces(session, 0, &count, nullptr), "xrEnumerateReferenceSpaces");
  std::vector<XrReferenceSpaceType> types(count);
  check(xrEnumerateReferenceSpaces(session, count, &count, types.data()), "xrEnumerateReferenceSpaces");
  return std::find(types.begin(), types.end(), XR_REFERENCE_SPACE_TYPE_STAGE) != types.end()
             ? XR_REFERENCE_SPACE_TYPE_STAGE
             : XR_REFERENCE_SPACE_TYPE_LOCAL;
}

std::vector<std::int64_t> swapchainFormats(XrSession session) {
  std::uint32_t count = 0;
  check(xrEnumerateSwapchainFormats(session, 0, &count, nullptr), "xrEnumerateSwapchainFormats");
  std::vector<std::int64_t> formats(count);
  check(xrEnumerateSwapchainFormats(session, count, &count, formats.data()), "xrEnumerateSwapchainFormats");
  return formats;
}

VkFormat colourFormat(const std::vector<std::int64_t>& formats) {
  // The renderer's colour is RGBA8: a copy keeps its bytes into either of these.
  for (const VkFormat wanted : {VK_FORMAT_R8G8B8A8_SRGB, VK_FORMAT_R8G8B8A8_UNORM}) {
    if (std::find(formats.begin(), formats.end(), static_cast<std::int64_t>(wanted)) != formats.end()) return wanted;
  }
  throw Error("the OpenXR runtime offers no RGBA8 swapchain format");
}

const char* stateName(XrSessionState state) {
  switch (state) {
    case XR_SESSION_STATE_IDLE:
      return "idle";
    case XR_SESSION_STATE_READY:
      return "ready";
    case XR_SESSION_STATE_SYNCHRONIZED:
      return "synchronized";
    case XR_SESSION_STATE_VISIBLE:
      return "visible";
    case XR_SESSION_STATE_FOCUSED:
      return "focused";
    case XR_SESSION_STATE_STOPPING:
      return "stopping";
    case XR_SESSION_STATE_LOSS_PENDING:
      return "lost";
    case XR_SESSION_STATE_EXITING:
      return "exiting";
    default:
      return "unknown";
  }
}

}  // namespace

Session::Session(Runtime& runtime, const gpu::Instance& instance, const gpu::Device& device, double resolution_scale)
    : runtime_(runtime) {
  auto binding = xrStruct<XrGraphicsBindingVulkan2KHR>(XR_TYPE_GRAPHICS_BINDING_VULKAN2_KHR);
  binding.instance = instance.handle();
  binding.physicalDevice = device.physical();
  binding.device = device.handle();
  binding.queueFamilyIndex = device.queueFamily();
  binding.queueIndex = 0;
  auto create = xrStruct<XrSessionCreateInfo>(XR_TYPE_SESSION_CREATE_INFO);
  create.next = &binding;
  create.systemId = runtime.system();
  check(xrCreateSession(runtime.instance(), &create, &session_), "starting a session on " + runtime.name());
  try {
    stage_ = referenceSpace(session_, stageType(session_));
    view_space_ = referenceSpace(session_, XR_REFERENCE_SPACE_TYPE_VIEW);

    std::uint32_t count = 0;
    check(xrEnumerateViewConfigurationViews(runtime.instance(), runtime.system(), kStereo, 0, &count, nullptr),
          "xrEnumerateViewConfigurationViews");
    if (count != kEyes) throw Error(runtime.name() + " has " + std::to_string(count) + " views, not two eyes");
    std::array<XrViewConfigurationView, kEyes> views{};
    for (XrViewConfigurationView& view : views) view.type = XR_TYPE_VIEW_CONFIGURATION_VIEW;
    check(xrEnumerateViewConfigurationViews(runtime.instance(), runtime.system(), kStereo, count, &count, views.data()),
          "xrEnumerateViewConfigurationViews");
    const auto scaled = [&](std::uint32_t recommended, std::uint32_t most) {
      const double size = std::round(recommended * std::clamp(resolution_scale, 0.1, 1.0));
      return std::clamp<std::uint32_t>(static_cast<std::uint32_t>(size), 16, most);
    };
    extent_ = {scaled(views[0].recommendedImageRectWidth, views[0].maxImageRectWidth),
               scaled(views[0].recommendedImageRectHeight, views[0].maxImageRectHeight)};
    formats_ = swapchainFormats(session_);
    format_ = colourFormat(formats_);
    for (Swapchain& swapchain : swapchains_) swapchain = createSwapchain(extent_, format_);
    // Depth for the runtime's reprojection, where it takes it, in a format without stencil.
    if (runtime.depthLayers()) {
      for (const VkFormat depth : {VK_FORMAT_D32_SFLOAT, VK_FORMAT_D16_UNORM}) {
        if (std::find(formats_.begin(), formats_.end(), static_cast<std::int64_t>(depth)) != formats_.end()) {
          depth_format_ = depth;
          break;
        }
      }
    }
    if (depth_format_ != VK_FORMAT_UNDEFINED) {
      for (Swapchain& swapchain : depth_swapchains_) {
        swapchain = createSwapchain(extent_, depth_format_, XR_SWAPCHAIN_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT);
      }
    }
    input_ = std::make_unique<Input>(runtime.instance(), session_);
  } catch (...) {
    destroy();
    throw;
  }
}

Session::~Session() {
  destroy();
}

Session::Swapchain Session::createSwapchain(VkExtent2D extent, VkFormat format, XrSwapchainUsageFlags usage) const {
  auto info = xrStruct<XrSwapchainCreateInfo>(XR_TYPE_SWAPCHAIN_CREATE_INFO);
  info.usageFlags = usage;
  info.format = format;
  info.sampleCount = 1;
  info.width = extent.width;
  info.height = extent.height;
  info.faceCount = 1;
  info.arraySize = 1;
  info.mipCount = 1;
  Swapchain swapchain;
  check(xrCreateSwapchain(session_, &info, &swapchain.handle), "xrCreateSwapchain");
  try {
    std::uint32_t images = 0;
    check(xrEnumerateSwapchainImages(swapchain.handle, 0, &images, nullptr), "xrEnumerateSwapchainImages");
    std::vector<XrSwapchainImageVulkan2KHR> vulkan(images, {XR_TYPE_SWAPCHAIN_IMAGE_VULKAN2_KHR, nullptr, {}});
    check(xrEnumerateSwapchainImages(swapchain.handle, images, &images,
                                     reinterpret_cast<XrSwapchainImageBaseHeader*>(vulkan.data())),
          "xrEnumerateSwapchainImages");
    for (const XrSwapchainImageVulkan2KHR& image : vulkan) swapchain.images.push_back(image.image);
  } catch (...) {
    xrDestroySwapchain(swapchain.handle);
    throw;
  }
  return swapchain;
}

bool Session::preparePanel(VkExtent2D extent, VkFormat format) {
  if (std::find(formats_.begin(), formats_.end(), static_cast<std::int64_t>(format)) == formats_.end()) return false;
  if (panel_.handle != XR_NULL_HANDLE && panel_extent_.width == extent.width && panel_extent_.height == extent.height &&
      panel_format_ == format) {
    return true;
  }
  if (panel_.handle != XR_NULL_HANDLE) xrDestroySwapchain(panel_.handle);
  panel_ = {};
  panel_ = createSwapchain(extent, format);
  panel_extent_ = extent;
  panel_format_ = format;
  return true;
}

gpu::SwapchainImage Session::acquirePanel() {
  return acquire(panel_, panel_extent_, panel_format_);
}

void Session::releasePanel() {
  auto release = xrStruct<XrSwapchainImageReleaseInfo>(XR_TYPE_SWAPCHAIN_IMAGE_RELEASE_INFO);
  check(xrReleaseSwapchainImage(panel_.handle, &release), "xrReleaseSwapchainImage (panel)");
}

void Session::destroy() {
  input_.reset();
  if (panel_.handle != XR_NULL_HANDLE) xrDestroySwapchain(panel_.handle);
  panel_.handle = XR_NULL_HANDLE;
  for (Swapchain& swapchain : depth_swapchains_) {
    if (swapchain.handle != XR_NULL_HANDLE) xrDestroySwapchain(swapchain.handle);
    swapchain.handle = XR_NULL_HANDLE;
  }
  for (Swapchain& swapchain : swapchains_) {
    if (swapchain.handle != XR_NULL_HANDLE) xrDestroySwapchain(swapchain.handle);
    swapchain.handle = XR_NULL_HANDLE;
  }
  if (view_space_ != XR_NULL_HANDLE) xrDestroySpace(view_space_);
  if (stage_ != XR_NULL_HANDLE) xrDestroySpace(stage_);
  view_space_ = stage_ = XR_NULL_HANDLE;
  if (session_ != XR_NULL_HANDLE) xrDestroySession(session_);
  session_ = XR_NULL_HANDLE;
}

SessionState Session::poll(std::vector<std::string>& messages) {
  messages.clear();
  auto event = xrStruct<XrEventDataBuffer>(XR_TYPE_EVENT_DATA_BUFFER);
  while (check(xrPollEvent(runtime_.instance(), &event), "xrPollEvent") == XR_SUCCESS) {
    if (event.type == XR_TYPE_EVENT_DATA_INSTANCE_LOSS_PENDING) {
      state_ = SessionState::kEnded;
      messages.push_back(runtime_.name() + " is going away: the headset session ended");
    } else if (event.type == XR_TYPE_EVENT_DATA_SESSION_STATE_CHANGED) {
      const auto& changed = reinterpret_cast<const XrEventDataSessionStateChanged&>(event);
      switch (changed.state) {
        case XR_SESSION_STATE_READY: {
          auto begin = xrStruct<XrSessionBeginInfo>(XR_TYPE_SESSION_BEGIN_INFO);
          begin.primaryViewConfigurationType = kStereo;
          check(xrBeginSession(session_, &begin), "xrBeginSession");
          state_ = SessionState::kRunning;
          break;
        }
        case XR_SESSION_STATE_STOPPING:
          check(xrEndSession(session_), "xrEndSession");
          state_ = SessionState::kStopped;
          break;
        case XR_SESSION_STATE_EXITING:
        case XR_SESSION_STATE_LOSS_PENDING:
          state_ = SessionState::kEnded;
          break;
        default:
          break;
      }
      focused_ = changed.state == XR_SESSION_STATE_FOCUSED;
      messages.push_back(std::string("headset session ") + stateName(changed.state));
    }
    event = xrStruct<XrEventDataBuffer>(XR_TYPE_EVENT_DATA_BUFFER);
  }
  return state_;
}

void Session::requestExit() {
  if (state_ == SessionState::kRunning) {
    check(xrRequestExitSession(session_), "xrRequestExitSession");
  } else {
    state_ = SessionState::kEnded;  // not begun: nothing for the runtime to stop
  }
  exit_requested_ = true;
}

std::optional<HeadsetFrame> Session::beginFrame() {
  if (state_ != SessionState::kRunning) return std::nullopt;
  auto timing = xrStruct<XrFrameState>(XR_TYPE_FRAME_STATE);
  check(xrWaitFrame(session_, nullptr, &timing), "xrWaitFrame");
  check(xrBeginFrame(session_, nullptr), "xrBeginFrame");
  HeadsetFrame frame;
  frame.display_time = timing.predictedDisplayTime;
  frame.display_period = timing.predictedDisplayPeriod;
  frame.should_render = timing.shouldRender == XR_TRUE;
  if (!frame.should_render) return frame;

  auto locate = xrStruct<XrViewLocateInfo>(XR_TYPE_VIEW_LOCATE_INFO);
  locate.viewConfigurationType = kStereo;
  locate.displayTime = frame.display_time;
  locate.space = stage_;
  auto view_state = xrStruct<XrViewState>(XR_TYPE_VIEW_STATE);
  std::array<XrView, kEyes> views{};
  for (XrView& view : views) view.type = XR_TYPE_VIEW;
  std::uint32_t count = 0;
  check(xrLocateViews(session_, &locate, &view_state, kEyes, &count, views.data()), "xrLocateViews");
  const XrViewStateFlags tracked = XR_VIEW_STATE_ORIENTATION_VALID_BIT | XR_VIEW_STATE_POSITION_VALID_BIT;
  if (count != kEyes || (view_state.viewStateFlags & tracked) != tracked) {
    frame.should_render = false;  // tracking lost: a frame drawn from a stale pose would swim
    return frame;
  }
  for (int eye = 0; eye < kEyes; ++eye) {
    const XrView& view = views[static_cast<std::size_t>(eye)];
    frame.eyes[static_cast<std::size_t>(eye)] = {
        toPose(view.pose), {view.fov.angleLeft, view.fov.angleRight, view.fov.angleUp, view.fov.angleDown}};
  }
  auto head = xrStruct<XrSpaceLocation>(XR_TYPE_SPACE_LOCATION);
  check(xrLocateSpace(view_space_, stage_, frame.display_time, &head), "xrLocateSpace (head)");
  frame.head = toPose(head.pose);
  input_->sync(stage_, frame.display_time, focused_);
  return frame;
}

gpu::SwapchainImage Session::acquireEye(int eye) {
  gpu::SwapchainImage image = acquire(swapchains_[static_cast<std::size_t>(eye)], extent_, format_);
  Swapchain& depth = depth_swapchains_[static_cast<std::size_t>(eye)];
  if (depth.handle != XR_NULL_HANDLE) {
    image.depth = acquire(depth, extent_, depth_format_).image;
    image.depth_format = depth_format_;
  }
  return image;
}

gpu::SwapchainImage Session::acquire(Swapchain& swapchain, VkExtent2D extent, VkFormat format) {
  auto acquire = xrStruct<XrSwapchainImageAcquireInfo>(XR_TYPE_SWAPCHAIN_IMAGE_ACQUIRE_INFO);
  check(xrAcquireSwapchainImage(swapchain.handle, &acquire, &swapchain.acquired), "xrAcquireSwapchainImage");
  auto wait = xrStruct<XrSwapchainImageWaitInfo>(XR_TYPE_SWAPCHAIN_IMAGE_WAIT_INFO);
  wait.timeout = XR_INFINITE_DURATION;
  check(xrWaitSwapchainImage(swapchain.handle, &wait), "xrWaitSwapchainImage");
  gpu::SwapchainImage image{};
  image.image = swapchain.images.at(swapchain.acquired);
  image.index = swapchain.acquired;
  image.extent = extent;
  image.format = format;
  image.acquired = VK_NULL_HANDLE;
  image.rendered = VK_NULL_HANDLE;
  image.presented_layout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;  // XR_KHR_vulkan_enable2's contract
  image.decorated = false;
  return image;
}

void Session::releaseEye(int eye) {
  auto release = xrStruct<XrSwapchainImageReleaseInfo>(XR_TYPE_SWAPCHAIN_IMAGE_RELEASE_INFO);
  check(xrReleaseSwapchainImage(swapchains_[static_cast<std::size_t>(eye)].handle, &release),
        "xrReleaseSwapchainImage");
  const Swapchain& depth = depth_swapchains_[static_cast<std::size_t>(eye)];
  if (depth.handle != XR_NULL_HANDLE) {
    check(xrReleaseSwapchainImage(depth.handle, &release), "xrReleaseSwapchainImage (depth)");
  }
}

namespace {

XrPosef xrPose(const Pose& pose) {
  XrPosef result{};
  result.position = {static_cast<float>(pose.position.x()), static_cast<float>(pose.position.y()),
                     static_cast<float>(pose.position.z())};
  result.orientation = {static_cast<float>(pose.orientation.x()), static_cast<float>(pose.orientation.y()),
                        static_cast<float>(pose.orientation.z()), static_cast<float>(pose.orientation.w())};
  return result;
}

}  // namespace

void Session::endFrame(const HeadsetFrame& frame, bool rendered, const HandPanel* panel) {
  std::array<XrCompositionLayerProjectionView, kEyes> views{};
  std::array<XrCompositionLayerDepthInfoKHR, kEyes> depths{};
  auto layer = xrStruct<XrCompositionLayerProjection>(XR_TYPE_COMPOSITION_LAYER_PROJECTION);
  auto quad = xrStruct<XrCompositionLayerQuad>(XR_TYPE_COMPOSITION_LAYER_QUAD);
  std::vector<const XrCompositionLayerBaseHeader*> layers;
  if (rendered) {
    for (int eye = 0; eye < kEyes; ++eye) {
      const EyeView& located = frame.eyes[static_cast<std::size_t>(eye)];
      XrCompositionLayerProjectionView& view = views[static_cast<std::size_t>(eye)];
      view.type = XR_TYPE_COMPOSITION_LAYER_PROJECTION_VIEW;
      view.pose = xrPose(located.pose);
      view.fov = {static_cast<float>(located.fov.left), static_cast<float>(located.fov.right),
                  static_cast<float>(located.fov.up), static_cast<float>(located.fov.down)};
      view.subImage.swapchain = swapchains_[static_cast<std::size_t>(eye)].handle;
      view.subImage.imageRect = {{0, 0},
                                 {static_cast<std::int32_t>(extent_.width), static_cast<std::int32_t>(extent_.height)}};
      view.subImage.imageArrayIndex = 0;
      const Swapchain& depth_swapchain = depth_swapchains_[static_cast<std::size_t>(eye)];
      if (depth_swapchain.handle != XR_NULL_HANDLE) {
        // The depth image's values as the eyes' projections map view depth (near 0, far 1).
        XrCompositionLayerDepthInfoKHR& depth = depths[static_cast<std::size_t>(eye)];
        depth.type = XR_TYPE_COMPOSITION_LAYER_DEPTH_INFO_KHR;
        depth.subImage = view.subImage;
        depth.subImage.swapchain = depth_swapchain.handle;
        depth.minDepth = 0.0f;
        depth.maxDepth = 1.0f;
        depth.nearZ = static_cast<float>(frame.near_m);
        depth.farZ = static_cast<float>(frame.far_m);
        view.next = &depth;
      }
    }
    layer.space = stage_;
    layer.viewCount = kEyes;
    layer.views = views.data();
    layers.push_back(reinterpret_cast<const XrCompositionLayerBaseHeader*>(&layer));
  }
  if (panel != nullptr && panel_.handle != XR_NULL_HANDLE) {
    // Over the scene, its transparent parts showing it (the palette's gaps between panels).
    quad.layerFlags = XR_COMPOSITION_LAYER_BLEND_TEXTURE_SOURCE_ALPHA_BIT;
    quad.space = stage_;
    quad.eyeVisibility = XR_EYE_VISIBILITY_BOTH;
    quad.subImage.swapchain = panel_.handle;
    quad.subImage.imageRect = {
        {0, 0}, {static_cast<std::int32_t>(panel_extent_.width), static_cast<std::int32_t>(panel_extent_.height)}};
    quad.pose = xrPose(panel->pose);
    quad.size = {static_cast<float>(panel->width_m), static_cast<float>(panel->height_m)};
    layers.push_back(reinterpret_cast<const XrCompositionLayerBaseHeader*>(&quad));
  }
  auto end = xrStruct<XrFrameEndInfo>(XR_TYPE_FRAME_END_INFO);
  end.displayTime = frame.display_time;
  end.environmentBlendMode = XR_ENVIRONMENT_BLEND_MODE_OPAQUE;
  end.layerCount = static_cast<std::uint32_t>(layers.size());
  end.layers = layers.data();
  check(xrEndFrame(session_, &end), "xrEndFrame");
}

}  // namespace plumb::xr
