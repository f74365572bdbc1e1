#pragma once
// The OpenXR functions the simulated headset implements, named as the API names them (inside this
// namespace: the loader's exported functions of the same names are never called, see xr_api.h).
// xrGetInstanceProcAddr (proc_addr.cpp) hands them to the loader by name. Which file implements
// what, each following the OpenXR 1.0 specification's chapter of the same subject:
//   instance_entry_points.cpp   chapters 4 "Instance", 5 "System", 6 "Path Tree", 8 "View Configurations", events
//   vulkan_entry_points.cpp     chapter 12, section "XR_KHR_vulkan_enable2"
//   session_entry_points.cpp    chapter 9 "Session"
//   frame_entry_points.cpp      chapter 10 "Rendering": frame waiting and submission
//   space_entry_points.cpp      chapter 7 "Spaces", xrLocateViews
//   action_entry_points.cpp     chapter 11 "Input and Haptics"
//   swapchain_entry_points.cpp  chapter 10 "Rendering": swapchain image management

#include "tests/support/xr_headset/xr_api.h"

namespace plumb::xr_headset {

// Instance, system, paths, events, strings.
XrResult XRAPI_CALL xrGetInstanceProcAddr(XrInstance instance, const char* name, PFN_xrVoidFunction* function);
XrResult XRAPI_CALL xrEnumerateInstanceExtensionProperties(const char* layer_name, uint32_t capacity,
                                                           uint32_t* count_output, XrExtensionProperties* properties);
XrResult XRAPI_CALL xrCreateInstance(const XrInstanceCreateInfo* create_info, XrInstance* instance);
XrResult XRAPI_CALL xrDestroyInstance(XrInstance instance);
XrResult XRAPI_CALL xrGetInstanceProperties(XrInstance instance, XrInstanceProperties* properties);
XrResult XRAPI_CALL xrPollEvent(XrInstance instance, XrEventDataBuffer* event_data);
XrResult XRAPI_CALL xrResultToString(XrInstance instance, XrResult value, char buffer[XR_MAX_RESULT_STRING_SIZE]);
XrResult XRAPI_CALL xrStructureTypeToString(XrInstance instance, XrStructureType value,
                                            char buffer[XR_MAX_STRUCTURE_NAME_SIZE]);
XrResult XRAPI_CALL xrStringToPath(XrInstance instance, const char* path_string, XrPath* path);
XrResult XRAPI_CALL xrPathToString(XrInstance instance, XrPath path, uint32_t capacity, uint32_t* count_output,
                                   char* buffer);
XrResult XRAPI_CALL xrGetSystem(XrInstance instance, const XrSystemGetInfo* get_info, XrSystemId* system_id);
XrResult XRAPI_CALL xrGetSystemProperties(XrInstance instance, XrSystemId system_id, XrSystemProperties* properties);
XrResult XRAPI_CALL xrEnumerateViewConfigurations(XrInstance instance, XrSystemId system_id, uint32_t capacity,
                                                  uint32_t* count_output, XrViewConfigurationType* types);
XrResult XRAPI_CALL xrGetViewConfigurationProperties(XrInstance instance, XrSystemId system_id,
                                                     XrViewConfigurationType type,
                                                     XrViewConfigurationProperties* properties);
XrResult XRAPI_CALL xrEnumerateViewConfigurationViews(XrInstance instance, XrSystemId system_id,
                                                      XrViewConfigurationType type, uint32_t capacity,
                                                      uint32_t* count_output, XrViewConfigurationView* views);
XrResult XRAPI_CALL xrEnumerateEnvironmentBlendModes(XrInstance instance, XrSystemId system_id,
                                                     XrViewConfigurationType type, uint32_t capacity,
                                                     uint32_t* count_output, XrEnvironmentBlendMode* modes);

// XR_KHR_vulkan_enable2.
XrResult XRAPI_CALL xrGetVulkanGraphicsRequirements2KHR(XrInstance instance, XrSystemId system_id,
                                                        XrGraphicsRequirementsVulkanKHR* requirements);
XrResult XRAPI_CALL xrCreateVulkanInstanceKHR(XrInstance instance, const XrVulkanInstanceCreateInfoKHR* create_info,
                                              VkInstance* vulkan_instance, VkResult* vulkan_result);
XrResult XRAPI_CALL xrGetVulkanGraphicsDevice2KHR(XrInstance instance, const XrVulkanGraphicsDeviceGetInfoKHR* get_info,
                                                  VkPhysicalDevice* physical_device);
XrResult XRAPI_CALL xrCreateVulkanDeviceKHR(XrInstance instance, const XrVulkanDeviceCreateInfoKHR* create_info,
                                            VkDevice* vulkan_device, VkResult* vulkan_result);

// Sessions.
XrResult XRAPI_CALL xrCreateSession(XrInstance instance, const XrSessionCreateInfo* create_info, XrSession* session);
XrResult XRAPI_CALL xrDestroySession(XrSession session);
XrResult XRAPI_CALL xrBeginSession(XrSession session, const XrSessionBeginInfo* begin_info);
XrResult XRAPI_CALL xrEndSession(XrSession session);
XrResult XRAPI_CALL xrRequestExitSession(XrSession session);

// Frames.
XrResult XRAPI_CALL xrWaitFrame(XrSession session, const XrFrameWaitInfo* wait_info, XrFrameState* frame_state);
XrResult XRAPI_CALL xrBeginFrame(XrSession session, const XrFrameBeginInfo* begin_info);
XrResult XRAPI_CALL xrEndFrame(XrSession session, const XrFrameEndInfo* end_info);

// Spaces and views.
XrResult XRAPI_CALL xrEnumerateReferenceSpaces(XrSession session, uint32_t capacity, uint32_t* count_output,
                                               XrReferenceSpaceType* spaces);
XrResult XRAPI_CALL xrCreateReferenceSpace(XrSession session, const XrReferenceSpaceCreateInfo* create_info,
                                           XrSpace* space);
XrResult XRAPI_CALL xrGetReferenceSpaceBoundsRect(XrSession session, XrReferenceSpaceType type, XrExtent2Df* bounds);
XrResult XRAPI_CALL xrCreateActionSpace(XrSession session, const XrActionSpaceCreateInfo* create_info, XrSpace* space);
XrResult XRAPI_CALL xrDestroySpace(XrSpace space);
XrResult XRAPI_CALL xrLocateSpace(XrSpace space, XrSpace base_space, XrTime time, XrSpaceLocation* location);
XrResult XRAPI_CALL xrLocateViews(XrSession session, const XrViewLocateInfo* locate_info, XrViewState* view_state,
                                  uint32_t capacity, uint32_t* count_output, XrView* views);

// Actions.
XrResult XRAPI_CALL xrCreateActionSet(XrInstance instance, const XrActionSetCreateInfo* create_info,
                                      XrActionSet* action_set);
XrResult XRAPI_CALL xrDestroyActionSet(XrActionSet action_set);
XrResult XRAPI_CALL xrCreateAction(XrActionSet action_set, const XrActionCreateInfo* create_info, XrAction* action);
XrResult XRAPI_CALL xrDestroyAction(XrAction action);
XrResult XRAPI_CALL xrSuggestInteractionProfileBindings(XrInstance instance,
                                                        const XrInteractionProfileSuggestedBinding* suggested);
XrResult XRAPI_CALL xrAttachSessionActionSets(XrSession session, const XrSessionActionSetsAttachInfo* attach_info);
XrResult XRAPI_CALL xrGetCurrentInteractionProfile(XrSession session, XrPath top_level_user_path,
                                                   XrInteractionProfileState* profile);
XrResult XRAPI_CALL xrSyncActions(XrSession session, const XrActionsSyncInfo* sync_info);
XrResult XRAPI_CALL xrGetActionStateBoolean(XrSession session, const XrActionStateGetInfo* get_info,
                                            XrActionStateBoolean* state);
XrResult XRAPI_CALL xrGetActionStateFloat(XrSession session, const XrActionStateGetInfo* get_info,
                                          XrActionStateFloat* state);
XrResult XRAPI_CALL xrGetActionStateVector2f(XrSession session, const XrActionStateGetInfo* get_info,
                                             XrActionStateVector2f* state);
XrResult XRAPI_CALL xrGetActionStatePose(XrSession session, const XrActionStateGetInfo* get_info,
                                         XrActionStatePose* state);
XrResult XRAPI_CALL xrEnumerateBoundSourcesForAction(XrSession session,
                                                     const XrBoundSourcesForActionEnumerateInfo* enumerate_info,
                                                     uint32_t capacity, uint32_t* count_output, XrPath* sources);
XrResult XRAPI_CALL xrGetInputSourceLocalizedName(XrSession session, const XrInputSourceLocalizedNameGetInfo* get_info,
                                                  uint32_t capacity, uint32_t* count_output, char* buffer);
XrResult XRAPI_CALL xrApplyHapticFeedback(XrSession session, const XrHapticActionInfo* action_info,
                                          const XrHapticBaseHeader* haptic);
XrResult XRAPI_CALL xrStopHapticFeedback(XrSession session, const XrHapticActionInfo* action_info);

// Swapchains.
XrResult XRAPI_CALL xrEnumerateSwapchainFormats(XrSession session, uint32_t capacity, uint32_t* count_output,
                                                int64_t* formats);
XrResult XRAPI_CALL xrCreateSwapchain(XrSession session, const XrSwapchainCreateInfo* create_info,
                                      XrSwapchain* swapchain);
XrResult XRAPI_CALL xrDestroySwapchain(XrSwapchain swapchain);
XrResult XRAPI_CALL xrEnumerateSwapchainImages(XrSwapchain swapchain, uint32_t capacity, uint32_t* count_output,
                                               XrSwapchainImageBaseHeader* images);
XrResult XRAPI_CALL xrAcquireSwapchainImage(XrSwapchain swapchain, const XrSwapchainImageAcquireInfo* acquire_info,
                                            uint32_t* index);
XrResult XRAPI_CALL xrWaitSwapchainImage(XrSwapchain swapchain, const XrSwapchainImageWaitInfo* wait_info);
XrResult XRAPI_CALL xrReleaseSwapchainImage(XrSwapchain swapchain, const XrSwapchainImageReleaseInfo* release_info);

}  // namespace plumb::xr_headset
