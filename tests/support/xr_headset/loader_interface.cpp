// How the OpenXR loader reaches the simulated headset: the exported negotiation function ("OpenXR
// Loader - Design and Operation", section "Runtime Interface Negotiation"; OpenXR 1.0 reference
// page xrNegotiateLoaderRuntimeInterface) and xrGetInstanceProcAddr (OpenXR 1.0 specification,
// section 3.2 "Function Pointers": with XR_NULL_HANDLE only the functions that create an instance
// or enumerate its extensions; an extension's functions only when the instance enabled it).

#include "tests/support/xr_headset/loader_interface.h"

#include <cstring>
#include <string_view>

#include "tests/support/xr_headset/entry_points.h"
#include "tests/support/xr_headset/runtime_state.h"

namespace plumb::xr_headset {
namespace {

enum class Needs { kNothing, kVulkanEnable2 };

struct NamedFunction {
  std::string_view name;
  PFN_xrVoidFunction function;
  Needs needs = Needs::kNothing;
};

template <class Function>
PFN_xrVoidFunction asVoidFunction(Function* function) {
  // PFN_xrVoidFunction is the API's generic function pointer type: the caller casts it back.
  return reinterpret_cast<PFN_xrVoidFunction>(function);
}

#define PLUMB_XR_FUNCTION(name) \
  { #name, asVoidFunction(&name), Needs::kNothing }
#define PLUMB_XR_VULKAN_FUNCTION(name) \
  { #name, asVoidFunction(&name), Needs::kVulkanEnable2 }

const NamedFunction kFunctions[] = {
    PLUMB_XR_FUNCTION(xrGetInstanceProcAddr),
    PLUMB_XR_FUNCTION(xrEnumerateInstanceExtensionProperties),
    PLUMB_XR_FUNCTION(xrCreateInstance),
    PLUMB_XR_FUNCTION(xrDestroyInstance),
    PLUMB_XR_FUNCTION(xrGetInstanceProperties),
    PLUMB_XR_FUNCTION(xrPollEvent),
    PLUMB_XR_FUNCTION(xrResultToString),
    PLUMB_XR_FUNCTION(xrStructureTypeToString),
    PLUMB_XR_FUNCTION(xrStringToPath),
    PLUMB_XR_FUNCTION(xrPathToString),
    PLUMB_XR_FUNCTION(xrGetSystem),
    PLUMB_XR_FUNCTION(xrGetSystemProperties),
    PLUMB_XR_FUNCTION(xrEnumerateViewConfigurations),
    PLUMB_XR_FUNCTION(xrGetViewConfigurationProperties),
    PLUMB_XR_FUNCTION(xrEnumerateViewConfigurationViews),
    PLUMB_XR_FUNCTION(xrEnumerateEnvironmentBlendModes),
    PLUMB_XR_VULKAN_FUNCTION(xrGetVulkanGraphicsRequirements2KHR),
    PLUMB_XR_VULKAN_FUNCTION(xrCreateVulkanInstanceKHR),
    PLUMB_XR_VULKAN_FUNCTION(xrGetVulkanGraphicsDevice2KHR),
    PLUMB_XR_VULKAN_FUNCTION(xrCreateVulkanDeviceKHR),
    PLUMB_XR_FUNCTION(xrCreateSession),
    PLUMB_XR_FUNCTION(xrDestroySession),
    PLUMB_XR_FUNCTION(xrBeginSession),
    PLUMB_XR_FUNCTION(xrEndSession),
    PLUMB_XR_FUNCTION(xrRequestExitSession),
    PLUMB_XR_FUNCTION(xrWaitFrame),
    PLUMB_XR_FUNCTION(xrBeginFrame),
    PLUMB_XR_FUNCTION(xrEndFrame),
    PLUMB_XR_FUNCTION(xrEnumerateReferenceSpaces),
    PLUMB_XR_FUNCTION(xrCreateReferenceSpace),
    PLUMB_XR_FUNCTION(xrGetReferenceSpaceBoundsRect),
    PLUMB_XR_FUNCTION(xrCreateActionSpace),
    PLUMB_XR_FUNCTION(xrDestroySpace),
    PLUMB_XR_FUNCTION(xrLocateSpace),
    PLUMB_XR_FUNCTION(xrLocateViews),
    PLUMB_XR_FUNCTION(xrCreateActionSet),
    PLUMB_XR_FUNCTION(xrDestroyActionSet),
    PLUMB_XR_FUNCTION(xrCreateAction),
    PLUMB_XR_FUNCTION(xrDestroyAction),
    PLUMB_XR_FUNCTION(xrSuggestInteractionProfileBindings),
    PLUMB_XR_FUNCTION(xrAttachSessionActionSets),
    PLUMB_XR_FUNCTION(xrGetCurrentInteractionProfile),
    PLUMB_XR_FUNCTION(xrSyncActions),
    PLUMB_XR_FUNCTION(xrGetActionStateBoolean),
    PLUMB_XR_FUNCTION(xrGetActionStateFloat),
    PLUMB_XR_FUNCTION(xrGetActionStateVector2f),
    PLUMB_XR_FUNCTION(xrGetActionStatePose),
    PLUMB_XR_FUNCTION(xrEnumerateBoundSourcesForAction),
    PLUMB_XR_FUNCTION(xrGetInputSourceLocalizedName),
    PLUMB_XR_FUNCTION(xrApplyHapticFeedback),
    PLUMB_XR_FUNCTION(xrStopHapticFeedback),
    PLUMB_XR_FUNCTION(xrEnumerateSwapchainFormats),
    PLUMB_XR_FUNCTION(xrCreateSwapchain),
    PLUMB_XR_FUNCTION(xrDestroySwapchain),
    PLUMB_XR_FUNCTION(xrEnumerateSwapchainImages),
    PLUMB_XR_FUNCTION(xrAcquireSwapchainImage),
    PLUMB_XR_FUNCTION(xrWaitSwapchainImage),
    PLUMB_XR_FUNCTION(xrReleaseSwapchainImage),
};

#undef PLUMB_XR_FUNCTION
#undef PLUMB_XR_VULKAN_FUNCTION

const NamedFunction* lookUp(std::string_view name) {
  for (const NamedFunction& entry : kFunctions) {
    if (entry.name == name) return &entry;
  }
  return nullptr;
}

}  // namespace

XrResult XRAPI_CALL xrGetInstanceProcAddr(XrInstance instance, const char* name, PFN_xrVoidFunction* function) {
  constexpr const char* kSelf = "xrGetInstanceProcAddr";
  if (name == nullptr || function == nullptr) return misuse(XR_ERROR_VALIDATION_FAILURE, kSelf, "a null argument");
  *function = nullptr;
  const std::string_view wanted(name);
  const NamedFunction* entry = lookUp(wanted);
  if (instance == XR_NULL_HANDLE) {
    // Before an instance exists only these may be asked for; the loader implements
    // xrEnumerateApiLayerProperties itself.
    if (wanted != "xrEnumerateInstanceExtensionProperties" && wanted != "xrCreateInstance") {
      return wanted == "xrEnumerateApiLayerProperties" ? XR_ERROR_FUNCTION_UNSUPPORTED : XR_ERROR_HANDLE_INVALID;
    }
    *function = entry->function;
    return XR_SUCCESS;
  }
  std::lock_guard lock(runtime().mutex);
  const Instance* owner = find(runtime().instances, idOf(instance));
  if (owner == nullptr) return misuse(XR_ERROR_HANDLE_INVALID, kSelf, "unknown XrInstance");
  // Unknown names are the loader's normal probing of every function it knows: no stderr line.
  if (entry == nullptr) return XR_ERROR_FUNCTION_UNSUPPORTED;
  if (entry->needs == Needs::kVulkanEnable2 && !owner->vulkan_enable2) return XR_ERROR_FUNCTION_UNSUPPORTED;
  *function = entry->function;
  return XR_SUCCESS;
}

}  // namespace plumb::xr_headset

extern "C" XrResult xrNegotiateLoaderRuntimeInterface(const XrNegotiateLoaderInfo* loader_info,
                                                      XrNegotiateRuntimeRequest* runtime_request) {
  using plumb::xr_headset::misuse;
  constexpr const char* kSelf = "xrNegotiateLoaderRuntimeInterface";
  if (loader_info == nullptr || runtime_request == nullptr) {
    return misuse(XR_ERROR_INITIALIZATION_FAILED, kSelf, "a null argument");
  }
  if (loader_info->structType != XR_LOADER_INTERFACE_STRUCT_LOADER_INFO ||
      loader_info->structVersion != XR_LOADER_INFO_STRUCT_VERSION ||
      loader_info->structSize != sizeof(XrNegotiateLoaderInfo)) {
    return misuse(XR_ERROR_INITIALIZATION_FAILED, kSelf, "the loader's XrNegotiateLoaderInfo is not version 1");
  }
  if (runtime_request->structType != XR_LOADER_INTERFACE_STRUCT_RUNTIME_REQUEST ||
      runtime_request->structVersion != XR_RUNTIME_INFO_STRUCT_VERSION ||
      runtime_request->structSize != sizeof(XrNegotiateRuntimeRequest)) {
    return misuse(XR_ERROR_INITIALIZATION_FAILED, kSelf, "the loader's XrNegotiateRuntimeRequest is not version 1");
  }
  if (loader_info->minInterfaceVersion > XR_CURRENT_LOADER_RUNTIME_VERSION ||
      loader_info->maxInterfaceVersion < XR_CURRENT_LOADER_RUNTIME_VERSION) {
    return misuse(XR_ERROR_INITIALIZATION_FAILED, kSelf, "the loader does not speak runtime interface version 1");
  }
  // The runtime implements OpenXR 1.0: the loader's range must include 1.0 (patch ignored).
  constexpr XrVersion kApiMajorMinor = XR_MAKE_VERSION(1, 0, 0);
  constexpr XrVersion kMajorMinorBits = XR_MAKE_VERSION(0xffff, 0xffff, 0);
  if ((loader_info->minApiVersion & kMajorMinorBits) > kApiMajorMinor || loader_info->maxApiVersion < kApiMajorMinor) {
    return misuse(XR_ERROR_INITIALIZATION_FAILED, kSelf, "the loader does not accept OpenXR 1.0 runtimes");
  }
  runtime_request->runtimeInterfaceVersion = XR_CURRENT_LOADER_RUNTIME_VERSION;
  runtime_request->runtimeApiVersion = XR_CURRENT_API_VERSION;
  runtime_request->getInstanceProcAddr = &plumb::xr_headset::xrGetInstanceProcAddr;
  return XR_SUCCESS;
}
