// Instance, system, path, event and string entry points of the simulated headset. OpenXR 1.0
// specification: chapter 4 "Instance" (extensions, creation, properties, the enum-to-string
// functions), chapter 5 "System" (one HMD, XrSystemId 1), chapter 6 "Path Tree and Semantic Paths"
// (xrStringToPath, xrPathToString), chapter 8 "View Configurations" (primary stereo only, opaque
// blending), chapter 2 "Fundamentals", section "Event Polling" (xrPollEvent).
//
// xrCreateInstance also reads the headset's environment: PLUMB_XR_HEADSET_SCRIPT (the script,
// headset_script.h) and PLUMB_XR_HEADSET_OUT (the folder frame_output.h writes to).

#include <openxr/openxr_reflection.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <string>
#include <system_error>

#include "tests/support/xr_headset/entry_points.h"
#include "tests/support/xr_headset/runtime_state.h"

namespace plumb::xr_headset {
namespace {

struct OfferedExtension {
  const char* name;
  std::uint32_t version;
};

constexpr OfferedExtension kExtensions[] = {
    {XR_KHR_VULKAN_ENABLE2_EXTENSION_NAME, XR_KHR_vulkan_enable2_SPEC_VERSION},
    {XR_KHR_COMPOSITION_LAYER_DEPTH_EXTENSION_NAME, XR_KHR_composition_layer_depth_SPEC_VERSION},
};

constexpr XrVersion kRuntimeVersion = XR_MAKE_VERSION(0, 1, 0);

template <std::size_t kSize>
void copyString(char (&destination)[kSize], std::string_view text) {
  const std::size_t length = std::min(text.size(), kSize - 1);
  std::memcpy(destination, text.data(), length);
  destination[length] = '\0';
}

void copyString(char* destination, std::size_t size, std::string_view text) {
  const std::size_t length = std::min(text.size(), size - 1);
  std::memcpy(destination, text.data(), length);
  destination[length] = '\0';
}

std::string environment(const char* name) {
  const char* value = std::getenv(name);
  return value == nullptr ? std::string() : std::string(value);
}

// The instance and the system id checked, for the system and view configuration queries.
XrResult checkSystem(const char* function, XrInstance instance, XrSystemId system_id) {
  if (find(runtime().instances, idOf(instance)) == nullptr) {
    return misuse(XR_ERROR_HANDLE_INVALID, function, "unknown XrInstance");
  }
  if (system_id != kSystemId) return misuse(XR_ERROR_SYSTEM_INVALID, function, "unknown XrSystemId");
  return XR_SUCCESS;
}

XrResult checkViewConfiguration(const char* function, XrViewConfigurationType type) {
  if (type == XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO) return XR_SUCCESS;
  return misuse(XR_ERROR_VIEW_CONFIGURATION_TYPE_UNSUPPORTED, function,
                "only XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO is offered");
}

// The enumerants' names from openxr_reflection.h's lists; null for values the lists lack.
// clang-format off
#define PLUMB_XR_NAME_CASE(name, number) case name: return #name;
const char* resultName(XrResult value) {
  switch (value) { XR_LIST_ENUM_XrResult(PLUMB_XR_NAME_CASE) }
  return nullptr;
}
const char* structureTypeName(XrStructureType value) {
  switch (value) { XR_LIST_ENUM_XrStructureType(PLUMB_XR_NAME_CASE) }
  return nullptr;
}
#undef PLUMB_XR_NAME_CASE
// clang-format on

}  // namespace

XrResult XRAPI_CALL xrEnumerateInstanceExtensionProperties(const char* layer_name, uint32_t capacity,
                                                           uint32_t* count_output, XrExtensionProperties* properties) {
  constexpr const char* kSelf = "xrEnumerateInstanceExtensionProperties";
  if (layer_name != nullptr) return misuse(XR_ERROR_API_LAYER_NOT_PRESENT, kSelf, "the runtime has no API layers");
  if (capacity > 0 && properties == nullptr) return misuse(XR_ERROR_VALIDATION_FAILURE, kSelf, "null properties");
  return fillArray(kSelf, capacity, count_output, std::size(kExtensions), [&](std::uint32_t i) {
    if (properties[i].type != XR_TYPE_EXTENSION_PROPERTIES) {
      return misuse(XR_ERROR_VALIDATION_FAILURE, kSelf, "properties[] must have type XR_TYPE_EXTENSION_PROPERTIES");
    }
    copyString(properties[i].extensionName, kExtensions[i].name);
    properties[i].extensionVersion = kExtensions[i].version;
    return XR_SUCCESS;
  });
}

XrResult XRAPI_CALL xrCreateInstance(const XrInstanceCreateInfo* create_info, XrInstance* instance) {
  constexpr const char* kSelf = "xrCreateInstance";
  if (create_info == nullptr || instance == nullptr)
    return misuse(XR_ERROR_VALIDATION_FAILURE, kSelf, "a null argument");
  if (create_info->type != XR_TYPE_INSTANCE_CREATE_INFO) {
    return misuse(XR_ERROR_VALIDATION_FAILURE, kSelf, "createInfo must have type XR_TYPE_INSTANCE_CREATE_INFO");
  }
  if (create_info->createFlags != 0) return misuse(XR_ERROR_VALIDATION_FAILURE, kSelf, "createFlags must be 0");
  if (create_info->applicationInfo.applicationName[0] == '\0') {
    return misuse(XR_ERROR_NAME_INVALID, kSelf, "the application name is empty");
  }
  // A 1.0 runtime: the application's major.minor must be 1.0.
  if ((create_info->applicationInfo.apiVersion & XR_MAKE_VERSION(0xffff, 0xffff, 0)) != XR_MAKE_VERSION(1, 0, 0)) {
    return misuse(XR_ERROR_API_VERSION_UNSUPPORTED, kSelf, "the runtime implements OpenXR 1.0 only");
  }
  auto created = std::make_unique<Instance>();
  for (std::uint32_t i = 0; i < create_info->enabledExtensionCount; ++i) {
    const std::string_view name = create_info->enabledExtensionNames[i];
    if (name == XR_KHR_VULKAN_ENABLE2_EXTENSION_NAME) {
      created->vulkan_enable2 = true;
    } else if (name == XR_KHR_COMPOSITION_LAYER_DEPTH_EXTENSION_NAME) {
      created->depth_layers = true;
    } else {
      return misuse(XR_ERROR_EXTENSION_NOT_PRESENT, kSelf, "extension " + std::string(name) + " is not offered");
    }
  }

  const std::string script_path = environment("PLUMB_XR_HEADSET_SCRIPT");
  try {
    created->script = script_path.empty() ? defaultHeadsetScript() : loadHeadsetScript(script_path);
  } catch (const ScriptError& error) {
    return misuse(XR_ERROR_RUNTIME_FAILURE, kSelf, std::string("the script ") + error.what());
  }
  created->output_folder = environment("PLUMB_XR_HEADSET_OUT");
  if (!created->output_folder.empty()) {
    std::error_code error;
    std::filesystem::create_directories(created->output_folder, error);
    if (error) {
      return misuse(XR_ERROR_RUNTIME_FAILURE, kSelf,
                    "cannot create PLUMB_XR_HEADSET_OUT " + created->output_folder + ": " + error.message());
    }
  }
  if (!isWellFormedPath(created->script.profile)) {
    return misuse(XR_ERROR_RUNTIME_FAILURE, kSelf,
                  "the script " + script_path + ": profile: " + created->script.profile + " is not a well-formed path");
  }
  internPath(*created, created->script.profile);

  std::lock_guard lock(runtime().mutex);
  *instance = handleOf<XrInstance>(store(runtime().instances, std::move(created)));
  return XR_SUCCESS;
}

XrResult XRAPI_CALL xrDestroyInstance(XrInstance instance) {
  std::lock_guard lock(runtime().mutex);
  if (find(runtime().instances, idOf(instance)) == nullptr) {
    return misuse(XR_ERROR_HANDLE_INVALID, "xrDestroyInstance", "unknown XrInstance");
  }
  destroyInstance(idOf(instance));
  return XR_SUCCESS;
}

XrResult XRAPI_CALL xrGetInstanceProperties(XrInstance instance, XrInstanceProperties* properties) {
  constexpr const char* kSelf = "xrGetInstanceProperties";
  std::lock_guard lock(runtime().mutex);
  if (find(runtime().instances, idOf(instance)) == nullptr)
    return misuse(XR_ERROR_HANDLE_INVALID, kSelf, "unknown XrInstance");
  if (properties == nullptr || properties->type != XR_TYPE_INSTANCE_PROPERTIES) {
    return misuse(XR_ERROR_VALIDATION_FAILURE, kSelf, "instanceProperties must have type XR_TYPE_INSTANCE_PROPERTIES");
  }
  properties->runtimeVersion = kRuntimeVersion;
  copyString(properties->runtimeName, kRuntimeName);
  return XR_SUCCESS;
}

XrResult XRAPI_CALL xrPollEvent(XrInstance instance, XrEventDataBuffer* event_data) {
  constexpr const char* kSelf = "xrPollEvent";
  std::lock_guard lock(runtime().mutex);
  Instance* owner = find(runtime().instances, idOf(instance));
  if (owner == nullptr) return misuse(XR_ERROR_HANDLE_INVALID, kSelf, "unknown XrInstance");
  if (event_data == nullptr || event_data->type != XR_TYPE_EVENT_DATA_BUFFER) {
    return misuse(XR_ERROR_VALIDATION_FAILURE, kSelf, "eventData must have type XR_TYPE_EVENT_DATA_BUFFER");
  }
  if (owner->events.empty()) return XR_EVENT_UNAVAILABLE;
  *event_data = owner->events.front();
  owner->events.pop_front();
  return XR_SUCCESS;
}

XrResult XRAPI_CALL xrResultToString(XrInstance instance, XrResult value, char buffer[XR_MAX_RESULT_STRING_SIZE]) {
  std::lock_guard lock(runtime().mutex);
  if (find(runtime().instances, idOf(instance)) == nullptr) {
    return misuse(XR_ERROR_HANDLE_INVALID, "xrResultToString", "unknown XrInstance");
  }
  const char* name = resultName(value);
  // The specification's names for values it does not know.
  const std::string text = name != nullptr       ? std::string(name)
                           : XR_SUCCEEDED(value) ? "XR_UNKNOWN_SUCCESS_" + std::to_string(value)
                                                 : "XR_UNKNOWN_FAILURE_" + std::to_string(value);
  copyString(buffer, XR_MAX_RESULT_STRING_SIZE, text);
  return XR_SUCCESS;
}

XrResult XRAPI_CALL xrStructureTypeToString(XrInstance instance, XrStructureType value,
                                            char buffer[XR_MAX_STRUCTURE_NAME_SIZE]) {
  std::lock_guard lock(runtime().mutex);
  if (find(runtime().instances, idOf(instance)) == nullptr) {
    return misuse(XR_ERROR_HANDLE_INVALID, "xrStructureTypeToString", "unknown XrInstance");
  }
  const char* name = structureTypeName(value);
  const std::string text = name != nullptr ? std::string(name) : "XR_UNKNOWN_STRUCTURE_TYPE_" + std::to_string(value);
  copyString(buffer, XR_MAX_STRUCTURE_NAME_SIZE, text);
  return XR_SUCCESS;
}

XrResult XRAPI_CALL xrStringToPath(XrInstance instance, const char* path_string, XrPath* path) {
  constexpr const char* kSelf = "xrStringToPath";
  std::lock_guard lock(runtime().mutex);
  Instance* owner = find(runtime().instances, idOf(instance));
  if (owner == nullptr) return misuse(XR_ERROR_HANDLE_INVALID, kSelf, "unknown XrInstance");
  if (path_string == nullptr || path == nullptr) return misuse(XR_ERROR_VALIDATION_FAILURE, kSelf, "a null argument");
  if (!isWellFormedPath(path_string)) {
    return misuse(XR_ERROR_PATH_FORMAT_INVALID, kSelf, std::string("'") + path_string + "' is not a well-formed path");
  }
  *path = internPath(*owner, path_string);
  return XR_SUCCESS;
}

XrResult XRAPI_CALL xrPathToString(XrInstance instance, XrPath path, uint32_t capacity, uint32_t* count_output,
                                   char* buffer) {
  constexpr const char* kSelf = "xrPathToString";
  std::lock_guard lock(runtime().mutex);
  const Instance* owner = find(runtime().instances, idOf(instance));
  if (owner == nullptr) return misuse(XR_ERROR_HANDLE_INVALID, kSelf, "unknown XrInstance");
  const std::string* text = pathString(*owner, path);
  if (text == nullptr) return misuse(XR_ERROR_PATH_INVALID, kSelf, "unknown XrPath " + std::to_string(path));
  if (capacity > 0 && buffer == nullptr) return misuse(XR_ERROR_VALIDATION_FAILURE, kSelf, "null buffer");
  const auto size = static_cast<std::uint32_t>(text->size() + 1);  // with the terminating null
  const XrResult result = fillArray(kSelf, capacity, count_output, size, [](std::uint32_t) { return XR_SUCCESS; });
  if (result == XR_SUCCESS && capacity > 0) copyString(buffer, size, *text);
  return result;
}

XrResult XRAPI_CALL xrGetSystem(XrInstance instance, const XrSystemGetInfo* get_info, XrSystemId* system_id) {
  constexpr const char* kSelf = "xrGetSystem";
  std::lock_guard lock(runtime().mutex);
  if (find(runtime().instances, idOf(instance)) == nullptr)
    return misuse(XR_ERROR_HANDLE_INVALID, kSelf, "unknown XrInstance");
  if (get_info == nullptr || system_id == nullptr || get_info->type != XR_TYPE_SYSTEM_GET_INFO) {
    return misuse(XR_ERROR_VALIDATION_FAILURE, kSelf, "getInfo must have type XR_TYPE_SYSTEM_GET_INFO");
  }
  if (get_info->formFactor == XR_FORM_FACTOR_HANDHELD_DISPLAY) {
    return misuse(XR_ERROR_FORM_FACTOR_UNSUPPORTED, kSelf, "the simulated headset is a head-mounted display");
  }
  if (get_info->formFactor != XR_FORM_FACTOR_HEAD_MOUNTED_DISPLAY) {
    return misuse(XR_ERROR_VALIDATION_FAILURE, kSelf, "unknown XrFormFactor");
  }
  *system_id = kSystemId;
  return XR_SUCCESS;
}

XrResult XRAPI_CALL xrGetSystemProperties(XrInstance instance, XrSystemId system_id, XrSystemProperties* properties) {
  constexpr const char* kSelf = "xrGetSystemProperties";
  std::lock_guard lock(runtime().mutex);
  if (const XrResult checked = checkSystem(kSelf, instance, system_id); XR_FAILED(checked)) return checked;
  if (properties == nullptr || properties->type != XR_TYPE_SYSTEM_PROPERTIES) {
    return misuse(XR_ERROR_VALIDATION_FAILURE, kSelf, "properties must have type XR_TYPE_SYSTEM_PROPERTIES");
  }
  properties->systemId = kSystemId;
  properties->vendorId = 0;
  copyString(properties->systemName, kRuntimeName);
  properties->graphicsProperties.maxSwapchainImageWidth = kMaxSwapchainSizePx;
  properties->graphicsProperties.maxSwapchainImageHeight = kMaxSwapchainSizePx;
  properties->graphicsProperties.maxLayerCount = kMaxLayerCount;
  properties->trackingProperties.orientationTracking = XR_TRUE;
  properties->trackingProperties.positionTracking = XR_TRUE;
  return XR_SUCCESS;
}

XrResult XRAPI_CALL xrEnumerateViewConfigurations(XrInstance instance, XrSystemId system_id, uint32_t capacity,
                                                  uint32_t* count_output, XrViewConfigurationType* types) {
  constexpr const char* kSelf = "xrEnumerateViewConfigurations";
  std::lock_guard lock(runtime().mutex);
  if (const XrResult checked = checkSystem(kSelf, instance, system_id); XR_FAILED(checked)) return checked;
  if (capacity > 0 && types == nullptr)
    return misuse(XR_ERROR_VALIDATION_FAILURE, kSelf, "null viewConfigurationTypes");
  return fillArray(kSelf, capacity, count_output, 1, [&](std::uint32_t i) {
    types[i] = XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO;
    return XR_SUCCESS;
  });
}

XrResult XRAPI_CALL xrGetViewConfigurationProperties(XrInstance instance, XrSystemId system_id,
                                                     XrViewConfigurationType type,
                                                     XrViewConfigurationProperties* properties) {
  constexpr const char* kSelf = "xrGetViewConfigurationProperties";
  std::lock_guard lock(runtime().mutex);
  if (const XrResult checked = checkSystem(kSelf, instance, system_id); XR_FAILED(checked)) return checked;
  if (const XrResult checked = checkViewConfiguration(kSelf, type); XR_FAILED(checked)) return checked;
  if (properties == nullptr || properties->type != XR_TYPE_VIEW_CONFIGURATION_PROPERTIES) {
    return misuse(XR_ERROR_VALIDATION_FAILURE, kSelf,
                  "configurationProperties must have type XR_TYPE_VIEW_CONFIGURATION_PROPERTIES");
  }
  properties->viewConfigurationType = type;
  properties->fovMutable = XR_FALSE;
  return XR_SUCCESS;
}

XrResult XRAPI_CALL xrEnumerateViewConfigurationViews(XrInstance instance, XrSystemId system_id,
                                                      XrViewConfigurationType type, uint32_t capacity,
                                                      uint32_t* count_output, XrViewConfigurationView* views) {
  constexpr const char* kSelf = "xrEnumerateViewConfigurationViews";
  std::lock_guard lock(runtime().mutex);
  if (const XrResult checked = checkSystem(kSelf, instance, system_id); XR_FAILED(checked)) return checked;
  if (const XrResult checked = checkViewConfiguration(kSelf, type); XR_FAILED(checked)) return checked;
  if (capacity > 0 && views == nullptr) return misuse(XR_ERROR_VALIDATION_FAILURE, kSelf, "null views");
  const HeadsetScript& script = find(runtime().instances, idOf(instance))->script;
  return fillArray(kSelf, capacity, count_output, 2, [&](std::uint32_t i) {
    if (views[i].type != XR_TYPE_VIEW_CONFIGURATION_VIEW) {
      return misuse(XR_ERROR_VALIDATION_FAILURE, kSelf, "views[] must have type XR_TYPE_VIEW_CONFIGURATION_VIEW");
    }
    views[i].recommendedImageRectWidth = script.eye_width;
    views[i].recommendedImageRectHeight = script.eye_height;
    views[i].maxImageRectWidth = kMaxSwapchainSizePx;
    views[i].maxImageRectHeight = kMaxSwapchainSizePx;
    views[i].recommendedSwapchainSampleCount = 1;
    views[i].maxSwapchainSampleCount = 1;
    return XR_SUCCESS;
  });
}

XrResult XRAPI_CALL xrEnumerateEnvironmentBlendModes(XrInstance instance, XrSystemId system_id,
                                                     XrViewConfigurationType type, uint32_t capacity,
                                                     uint32_t* count_output, XrEnvironmentBlendMode* modes) {
  constexpr const char* kSelf = "xrEnumerateEnvironmentBlendModes";
  std::lock_guard lock(runtime().mutex);
  if (const XrResult checked = checkSystem(kSelf, instance, system_id); XR_FAILED(checked)) return checked;
  if (const XrResult checked = checkViewConfiguration(kSelf, type); XR_FAILED(checked)) return checked;
  if (capacity > 0 && modes == nullptr) return misuse(XR_ERROR_VALIDATION_FAILURE, kSelf, "null environmentBlendModes");
  return fillArray(kSelf, capacity, count_output, 1, [&](std::uint32_t i) {
    modes[i] = XR_ENVIRONMENT_BLEND_MODE_OPAQUE;
    return XR_SUCCESS;
  });
}

}  // namespace plumb::xr_headset
