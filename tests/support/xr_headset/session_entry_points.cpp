// Session entry points of the simulated headset (OpenXR 1.0 specification, chapter 9 "Session":
// sections "Session Creation", "Session Control" and "Session States"; chapter 12, section
// "XR_KHR_vulkan_enable2" for the graphics binding).
//
// The states it goes through:
//   xrCreateSession                IDLE, READY
//   first xrWaitFrame after begin  SYNCHRONIZED, VISIBLE, FOCUSED   (frame_entry_points.cpp)
//   script events                  FOCUSED <-> VISIBLE, STOPPING, LOSS_PENDING
//   end of an "exit" script or     (VISIBLE, SYNCHRONIZED,) STOPPING
//     xrRequestExitSession
//   xrEndSession                   IDLE, then EXITING: every stop here is for good
// One session per instance at a time, as one headset has.

#include <string>
#include <vector>

#include "tests/support/xr_headset/entry_points.h"
#include "tests/support/xr_headset/runtime_state.h"

namespace plumb::xr_headset {
namespace {

// The binding's device checked against what the instance handed out, and its queue looked up.
XrResult bindVulkan(const char* function, const Instance& instance, const XrGraphicsBindingVulkan2KHR& binding,
                    VulkanBinding& bound) {
  if (binding.instance == VK_NULL_HANDLE || binding.physicalDevice == VK_NULL_HANDLE ||
      binding.device == VK_NULL_HANDLE) {
    return misuse(XR_ERROR_GRAPHICS_DEVICE_INVALID, function, "the graphics binding has a null Vulkan handle");
  }
  if (instance.physical_device == VK_NULL_HANDLE || binding.physicalDevice != instance.physical_device) {
    return misuse(XR_ERROR_GRAPHICS_DEVICE_INVALID, function,
                  "the graphics binding's physicalDevice must be the one xrGetVulkanGraphicsDevice2KHR returned");
  }
  std::uint32_t family_count = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(binding.physicalDevice, &family_count, nullptr);
  std::vector<VkQueueFamilyProperties> families(family_count);
  vkGetPhysicalDeviceQueueFamilyProperties(binding.physicalDevice, &family_count, families.data());
  if (binding.queueFamilyIndex >= family_count || binding.queueIndex >= families[binding.queueFamilyIndex].queueCount) {
    return misuse(XR_ERROR_GRAPHICS_DEVICE_INVALID, function, "the graphics binding's queue does not exist");
  }
  bound.instance = binding.instance;
  bound.physical_device = binding.physicalDevice;
  bound.device = binding.device;
  bound.queue_family_index = binding.queueFamilyIndex;
  bound.queue_index = binding.queueIndex;
  vkGetDeviceQueue(binding.device, binding.queueFamilyIndex, binding.queueIndex, &bound.queue);
  return XR_SUCCESS;
}

}  // namespace

XrResult XRAPI_CALL xrCreateSession(XrInstance instance, const XrSessionCreateInfo* create_info, XrSession* session) {
  constexpr const char* kSelf = "xrCreateSession";
  std::lock_guard lock(runtime().mutex);
  const std::uint64_t instance_id = idOf(instance);
  Instance* owner = find(runtime().instances, instance_id);
  if (owner == nullptr) return misuse(XR_ERROR_HANDLE_INVALID, kSelf, "unknown XrInstance");
  if (create_info == nullptr || session == nullptr || create_info->type != XR_TYPE_SESSION_CREATE_INFO) {
    return misuse(XR_ERROR_VALIDATION_FAILURE, kSelf, "createInfo must have type XR_TYPE_SESSION_CREATE_INFO");
  }
  if (create_info->createFlags != 0) return misuse(XR_ERROR_VALIDATION_FAILURE, kSelf, "createFlags must be 0");
  if (create_info->systemId != kSystemId) return misuse(XR_ERROR_SYSTEM_INVALID, kSelf, "unknown XrSystemId");
  if (!owner->vulkan_enable2) {
    return misuse(XR_ERROR_GRAPHICS_DEVICE_INVALID, kSelf, "the simulated headset needs XR_KHR_vulkan_enable2");
  }
  if (!owner->graphics_requirements_queried) {
    return misuse(XR_ERROR_GRAPHICS_REQUIREMENTS_CALL_MISSING, kSelf,
                  "call xrGetVulkanGraphicsRequirements2KHR before creating a session");
  }
  const auto* binding = reinterpret_cast<const XrGraphicsBindingVulkan2KHR*>(
      findInChain(create_info->next, XR_TYPE_GRAPHICS_BINDING_VULKAN2_KHR));
  if (binding == nullptr) {
    return misuse(XR_ERROR_GRAPHICS_DEVICE_INVALID, kSelf, "no XrGraphicsBindingVulkan2KHR in createInfo's next chain");
  }
  if (owner->session != 0) {
    return misuse(XR_ERROR_LIMIT_REACHED, kSelf, "the headset has a session already: destroy it first");
  }
  auto created = std::make_unique<Session>();
  created->instance = instance_id;
  if (const XrResult bound = bindVulkan(kSelf, *owner, *binding, created->vulkan); XR_FAILED(bound)) return bound;
  created->commands = OneShotCommands::create(created->vulkan);
  if (created->commands == nullptr) return XR_ERROR_RUNTIME_FAILURE;

  Session& stored = *created;
  const std::uint64_t id = store(runtime().sessions, std::move(created));
  owner->session = id;
  changeState(*owner, id, stored, XR_SESSION_STATE_IDLE);
  changeState(*owner, id, stored, XR_SESSION_STATE_READY);
  *session = handleOf<XrSession>(id);
  return XR_SUCCESS;
}

XrResult XRAPI_CALL xrDestroySession(XrSession session) {
  std::lock_guard lock(runtime().mutex);
  if (find(runtime().sessions, idOf(session)) == nullptr) {
    return misuse(XR_ERROR_HANDLE_INVALID, "xrDestroySession", "unknown XrSession");
  }
  destroySession(idOf(session));
  return XR_SUCCESS;
}

XrResult XRAPI_CALL xrBeginSession(XrSession session, const XrSessionBeginInfo* begin_info) {
  constexpr const char* kSelf = "xrBeginSession";
  std::lock_guard lock(runtime().mutex);
  Session* found = nullptr;
  Instance* owner = nullptr;
  if (const XrResult checked = lookUpSession(kSelf, session, found, owner); XR_FAILED(checked)) return checked;
  if (begin_info == nullptr || begin_info->type != XR_TYPE_SESSION_BEGIN_INFO) {
    return misuse(XR_ERROR_VALIDATION_FAILURE, kSelf, "beginInfo must have type XR_TYPE_SESSION_BEGIN_INFO");
  }
  if (begin_info->primaryViewConfigurationType != XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO) {
    return misuse(XR_ERROR_VIEW_CONFIGURATION_TYPE_UNSUPPORTED, kSelf,
                  "only XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO is offered");
  }
  if (found->running) return misuse(XR_ERROR_SESSION_RUNNING, kSelf, "the session is running already");
  if (found->state != XR_SESSION_STATE_READY) {
    return misuse(XR_ERROR_SESSION_NOT_READY, kSelf, "wait for XR_SESSION_STATE_READY before beginning the session");
  }
  // A running session's frame calls start over (section "Session Control").
  found->running = true;
  found->frames_started = false;
  found->frame_waited = false;
  found->begun_frame.reset();
  return sessionSuccess(*found);
}

XrResult XRAPI_CALL xrEndSession(XrSession session) {
  constexpr const char* kSelf = "xrEndSession";
  std::lock_guard lock(runtime().mutex);
  Session* found = nullptr;
  Instance* owner = nullptr;
  if (const XrResult checked = lookUpSession(kSelf, session, found, owner); XR_FAILED(checked)) return checked;
  if (!found->running) return misuse(XR_ERROR_SESSION_NOT_RUNNING, kSelf, "the session is not running");
  if (found->state != XR_SESSION_STATE_STOPPING) {
    return misuse(XR_ERROR_SESSION_NOT_STOPPING, kSelf, "wait for XR_SESSION_STATE_STOPPING before ending the session");
  }
  found->running = false;
  found->frame_waited = false;
  found->begun_frame.reset();
  const std::uint64_t id = idOf(session);
  changeState(*owner, id, *found, XR_SESSION_STATE_IDLE);
  if (found->exiting) changeState(*owner, id, *found, XR_SESSION_STATE_EXITING);
  return XR_SUCCESS;
}

XrResult XRAPI_CALL xrRequestExitSession(XrSession session) {
  constexpr const char* kSelf = "xrRequestExitSession";
  std::lock_guard lock(runtime().mutex);
  Session* found = nullptr;
  Instance* owner = nullptr;
  if (const XrResult checked = lookUpSession(kSelf, session, found, owner); XR_FAILED(checked)) return checked;
  if (!found->running) return misuse(XR_ERROR_SESSION_NOT_RUNNING, kSelf, "the session is not running");
  stopSession(*owner, idOf(session), *found);
  return sessionSuccess(*found);
}

}  // namespace plumb::xr_headset
