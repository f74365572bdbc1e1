// Swapchain entry points of the simulated headset (OpenXR 1.0 specification, chapter 10
// "Rendering", section "Swapchain Image Management"; chapter 12, section "XR_KHR_vulkan_enable2"
// for the Vulkan images). Three images a swapchain (one for a static one), handed out in turn:
// acquire, wait and release go in acquisition order, and a call out of that order fails with
// XR_ERROR_CALL_ORDER_INVALID. The last released image is what a composition layer shows.

#include <algorithm>
#include <string>

#include "tests/support/xr_headset/entry_points.h"
#include "tests/support/xr_headset/runtime_state.h"

namespace plumb::xr_headset {
namespace {

// The swapchain behind `handle` and its session; lost sessions answer XR_ERROR_SESSION_LOST.
XrResult lookUpSwapchain(const char* function, XrSwapchain handle, Swapchain*& swapchain, Session*& session) {
  swapchain = find(runtime().swapchains, idOf(handle));
  if (swapchain == nullptr) return misuse(XR_ERROR_HANDLE_INVALID, function, "unknown XrSwapchain");
  Instance* owner = nullptr;
  return lookUpSession(function, handleOf<XrSession>(swapchain->session), session, owner);
}

XrResult checkCreateInfo(const char* function, const XrSwapchainCreateInfo& info) {
  constexpr XrSwapchainCreateFlags kKnownFlags =
      XR_SWAPCHAIN_CREATE_PROTECTED_CONTENT_BIT | XR_SWAPCHAIN_CREATE_STATIC_IMAGE_BIT;
  if ((info.createFlags & ~kKnownFlags) != 0)
    return misuse(XR_ERROR_VALIDATION_FAILURE, function, "unknown createFlags");
  if ((info.createFlags & XR_SWAPCHAIN_CREATE_PROTECTED_CONTENT_BIT) != 0) {
    return misuse(XR_ERROR_FEATURE_UNSUPPORTED, function, "protected content is not simulated");
  }
  const std::span<const VkFormat> formats = swapchainFormats();
  if (std::find(formats.begin(), formats.end(), static_cast<VkFormat>(info.format)) == formats.end()) {
    return misuse(XR_ERROR_SWAPCHAIN_FORMAT_UNSUPPORTED, function,
                  "format " + std::to_string(info.format) + " is not one xrEnumerateSwapchainFormats offers");
  }
  if (info.sampleCount != 1) return misuse(XR_ERROR_FEATURE_UNSUPPORTED, function, "sampleCount must be 1");
  if (info.width == 0 || info.height == 0 || info.width > kMaxSwapchainSizePx || info.height > kMaxSwapchainSizePx) {
    return misuse(XR_ERROR_VALIDATION_FAILURE, function,
                  "width and height must be 1 to " + std::to_string(kMaxSwapchainSizePx));
  }
  if (info.faceCount != 1) return misuse(XR_ERROR_VALIDATION_FAILURE, function, "faceCount must be 1");
  if (info.arraySize == 0 || info.mipCount == 0) {
    return misuse(XR_ERROR_VALIDATION_FAILURE, function, "arraySize and mipCount must be at least 1");
  }
  const bool depth = isDepthFormat(static_cast<VkFormat>(info.format));
  const XrSwapchainUsageFlags wrong_attachment =
      depth ? XR_SWAPCHAIN_USAGE_COLOR_ATTACHMENT_BIT : XR_SWAPCHAIN_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT;
  if ((info.usageFlags & wrong_attachment) != 0) {
    return misuse(
        XR_ERROR_VALIDATION_FAILURE, function,
        depth ? "a depth format cannot be a colour attachment" : "a colour format cannot be a depth attachment");
  }
  return XR_SUCCESS;
}

}  // namespace

XrResult XRAPI_CALL xrEnumerateSwapchainFormats(XrSession session, uint32_t capacity, uint32_t* count_output,
                                                int64_t* formats) {
  constexpr const char* kSelf = "xrEnumerateSwapchainFormats";
  std::lock_guard lock(runtime().mutex);
  Session* found = nullptr;
  Instance* owner = nullptr;
  if (const XrResult checked = lookUpSession(kSelf, session, found, owner); XR_FAILED(checked)) return checked;
  if (capacity > 0 && formats == nullptr) return misuse(XR_ERROR_VALIDATION_FAILURE, kSelf, "null formats");
  const std::span<const VkFormat> offered = swapchainFormats();
  const XrResult result =
      fillArray(kSelf, capacity, count_output, static_cast<std::uint32_t>(offered.size()), [&](std::uint32_t i) {
        formats[i] = offered[i];
        return XR_SUCCESS;
      });
  return XR_FAILED(result) ? result : sessionSuccess(*found);
}

XrResult XRAPI_CALL xrCreateSwapchain(XrSession session, const XrSwapchainCreateInfo* create_info,
                                      XrSwapchain* swapchain) {
  constexpr const char* kSelf = "xrCreateSwapchain";
  std::lock_guard lock(runtime().mutex);
  Session* found = nullptr;
  Instance* owner = nullptr;
  if (const XrResult checked = lookUpSession(kSelf, session, found, owner); XR_FAILED(checked)) return checked;
  if (create_info == nullptr || swapchain == nullptr || create_info->type != XR_TYPE_SWAPCHAIN_CREATE_INFO) {
    return misuse(XR_ERROR_VALIDATION_FAILURE, kSelf, "createInfo must have type XR_TYPE_SWAPCHAIN_CREATE_INFO");
  }
  if (const XrResult checked = checkCreateInfo(kSelf, *create_info); XR_FAILED(checked)) return checked;
  auto created = std::make_unique<Swapchain>();
  created->session = idOf(session);
  created->static_image = (create_info->createFlags & XR_SWAPCHAIN_CREATE_STATIC_IMAGE_BIT) != 0;
  created->spec.format = static_cast<VkFormat>(create_info->format);
  created->spec.width = create_info->width;
  created->spec.height = create_info->height;
  created->spec.array_size = create_info->arraySize;
  created->spec.mip_count = create_info->mipCount;
  created->spec.usage = create_info->usageFlags;
  created->spec.image_count = created->static_image ? 1 : kSwapchainImageCount;
  if (const XrResult made = SwapchainImages::create(found->vulkan, *found->commands, created->spec, created->images);
      XR_FAILED(made)) {
    return made;
  }
  *swapchain = handleOf<XrSwapchain>(store(runtime().swapchains, std::move(created)));
  return sessionSuccess(*found);
}

XrResult XRAPI_CALL xrDestroySwapchain(XrSwapchain swapchain) {
  std::lock_guard lock(runtime().mutex);
  if (find(runtime().swapchains, idOf(swapchain)) == nullptr) {
    return misuse(XR_ERROR_HANDLE_INVALID, "xrDestroySwapchain", "unknown XrSwapchain");
  }
  destroySwapchain(idOf(swapchain));
  return XR_SUCCESS;
}

XrResult XRAPI_CALL xrEnumerateSwapchainImages(XrSwapchain swapchain, uint32_t capacity, uint32_t* count_output,
                                               XrSwapchainImageBaseHeader* images) {
  constexpr const char* kSelf = "xrEnumerateSwapchainImages";
  std::lock_guard lock(runtime().mutex);
  Swapchain* found = nullptr;
  Session* session = nullptr;
  if (const XrResult checked = lookUpSwapchain(kSelf, swapchain, found, session); XR_FAILED(checked)) return checked;
  if (capacity > 0 && images == nullptr) return misuse(XR_ERROR_VALIDATION_FAILURE, kSelf, "null images");
  // A Vulkan session's images are XrSwapchainImageVulkan2KHR: the array's stride is that struct's.
  auto* vulkan_images = reinterpret_cast<XrSwapchainImageVulkan2KHR*>(images);
  const std::vector<VkImage>& owned = found->images->images();
  const XrResult result =
      fillArray(kSelf, capacity, count_output, static_cast<std::uint32_t>(owned.size()), [&](std::uint32_t i) {
        if (vulkan_images[i].type != XR_TYPE_SWAPCHAIN_IMAGE_VULKAN2_KHR) {
          return misuse(XR_ERROR_VALIDATION_FAILURE, kSelf,
                        "images[] must have type XR_TYPE_SWAPCHAIN_IMAGE_VULKAN2_KHR");
        }
        vulkan_images[i].image = owned[i];
        return XR_SUCCESS;
      });
  return XR_FAILED(result) ? result : sessionSuccess(*session);
}

XrResult XRAPI_CALL xrAcquireSwapchainImage(XrSwapchain swapchain, const XrSwapchainImageAcquireInfo* acquire_info,
                                            uint32_t* index) {
  constexpr const char* kSelf = "xrAcquireSwapchainImage";
  std::lock_guard lock(runtime().mutex);
  Swapchain* found = nullptr;
  Session* session = nullptr;
  if (const XrResult checked = lookUpSwapchain(kSelf, swapchain, found, session); XR_FAILED(checked)) return checked;
  if (index == nullptr || (acquire_info != nullptr && acquire_info->type != XR_TYPE_SWAPCHAIN_IMAGE_ACQUIRE_INFO)) {
    return misuse(XR_ERROR_VALIDATION_FAILURE, kSelf,
                  "acquireInfo must be null or of type XR_TYPE_SWAPCHAIN_IMAGE_ACQUIRE_INFO");
  }
  if (found->static_image && found->acquire_count > 0) {
    return misuse(XR_ERROR_CALL_ORDER_INVALID, kSelf, "a static swapchain's image is acquired once only");
  }
  const std::uint32_t held = static_cast<std::uint32_t>(found->acquired.size()) + (found->waited ? 1u : 0u);
  if (held >= found->spec.image_count) {
    return misuse(XR_ERROR_CALL_ORDER_INVALID, kSelf, "every image is acquired already: release one first");
  }
  *index = found->next_index;
  found->acquired.push_back(found->next_index);
  found->next_index = (found->next_index + 1) % found->spec.image_count;
  ++found->acquire_count;
  return sessionSuccess(*session);
}

XrResult XRAPI_CALL xrWaitSwapchainImage(XrSwapchain swapchain, const XrSwapchainImageWaitInfo* wait_info) {
  constexpr const char* kSelf = "xrWaitSwapchainImage";
  std::lock_guard lock(runtime().mutex);
  Swapchain* found = nullptr;
  Session* session = nullptr;
  if (const XrResult checked = lookUpSwapchain(kSelf, swapchain, found, session); XR_FAILED(checked)) return checked;
  if (wait_info == nullptr || wait_info->type != XR_TYPE_SWAPCHAIN_IMAGE_WAIT_INFO) {
    return misuse(XR_ERROR_VALIDATION_FAILURE, kSelf, "waitInfo must have type XR_TYPE_SWAPCHAIN_IMAGE_WAIT_INFO");
  }
  if (found->waited) return misuse(XR_ERROR_CALL_ORDER_INVALID, kSelf, "the waited image is not released yet");
  if (found->acquired.empty()) return misuse(XR_ERROR_CALL_ORDER_INVALID, kSelf, "no image is acquired");
  // Images are never busy here: the readback waits for its own work before xrEndFrame returns.
  found->waited = found->acquired.front();
  found->acquired.pop_front();
  return sessionSuccess(*session);
}

XrResult XRAPI_CALL xrReleaseSwapchainImage(XrSwapchain swapchain, const XrSwapchainImageReleaseInfo* release_info) {
  constexpr const char* kSelf = "xrReleaseSwapchainImage";
  std::lock_guard lock(runtime().mutex);
  Swapchain* found = nullptr;
  Session* session = nullptr;
  if (const XrResult checked = lookUpSwapchain(kSelf, swapchain, found, session); XR_FAILED(checked)) return checked;
  if (release_info != nullptr && release_info->type != XR_TYPE_SWAPCHAIN_IMAGE_RELEASE_INFO) {
    return misuse(XR_ERROR_VALIDATION_FAILURE, kSelf,
                  "releaseInfo must be null or of type XR_TYPE_SWAPCHAIN_IMAGE_RELEASE_INFO");
  }
  if (!found->waited)
    return misuse(XR_ERROR_CALL_ORDER_INVALID, kSelf, "no image is waited on: call xrWaitSwapchainImage first");
  found->released = found->waited;
  found->waited.reset();
  return sessionSuccess(*session);
}

}  // namespace plumb::xr_headset
