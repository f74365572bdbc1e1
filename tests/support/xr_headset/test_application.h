#pragma once
// The application side of the simulated headset's tests (tests/xr/simulated_headset_test.cpp):
// raw OpenXR and raw Vulkan as an application uses them with a headset's runtime, through Khronos'
// OpenXR loader. Not part of the runtime library; header-only, for test executables. Its Vulkan
// instance has the validation layer on and records every warning and error it reports.
//
// The application creates the instance and device through XR_KHR_vulkan_enable2, one swapchain
// per eye (the left R8G8B8A8_SRGB, the right B8G8R8A8_UNORM), and on every rendered frame clears
// the left eye blue and the right eye red with greenOfFrame(frame) in its green, then submits a
// projection layer with the views xrLocateViews gave (and, on request, depth info and a quad).

#include <dlfcn.h>
#include <vulkan/vulkan.h>

#include <cstdint>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#ifndef XR_USE_GRAPHICS_API_VULKAN
#define XR_USE_GRAPHICS_API_VULKAN
#endif
#include <openxr/openxr.h>
#include <openxr/openxr_platform.h>

namespace plumb::test {

inline constexpr std::uint32_t kEyeWidthPx = 64, kEyeHeightPx = 48;

// Small helpers: failures throw, and GoogleTest reports the exception as the test's failure.

inline void check(XrResult result, const char* what) {
  if (XR_FAILED(result))
    throw std::runtime_error(std::string(what) + " failed with XrResult " + std::to_string(result));
}

inline void checkVk(VkResult result, const char* what) {
  if (result != VK_SUCCESS)
    throw std::runtime_error(std::string(what) + " failed with VkResult " + std::to_string(result));
}

template <class Function>
Function xrFunction(XrInstance instance, const char* name) {
  PFN_xrVoidFunction function = nullptr;
  check(xrGetInstanceProcAddr(instance, name, &function), name);
  return reinterpret_cast<Function>(function);
}

// Zeroed structures with their type set, as the APIs want them.
template <class Struct>
Struct xrStruct(XrStructureType type) {
  Struct value{};
  value.type = type;
  return value;
}

template <class Struct>
Struct vkStruct(VkStructureType type) {
  Struct value{};
  value.sType = type;
  return value;
}

// Mesa's lavapipe kept mapped for the process (as engine/gpu/instance.cpp does): its one-time
// global would otherwise be reported by LeakSanitizer after the loader unloads the driver.
inline void keepCpuDriverLoaded() {
  static void* const kept = dlopen("libvulkan_lvp.so", RTLD_NOW | RTLD_NODELETE);
  (void)kept;
}

// An application: what it saw, frame by frame.

struct FrameSeen {
  XrTime display_time = 0;
  XrBool32 should_render = XR_FALSE;
  XrResult wait_result = XR_SUCCESS;
  XrResult sync_result = XR_SUCCESS;
  XrActionStateFloat trigger = xrStruct<XrActionStateFloat>(XR_TYPE_ACTION_STATE_FLOAT);
  XrActionStatePose aim = xrStruct<XrActionStatePose>(XR_TYPE_ACTION_STATE_POSE);
  XrSpaceLocation aim_location = xrStruct<XrSpaceLocation>(XR_TYPE_SPACE_LOCATION);
  XrViewState view_state = xrStruct<XrViewState>(XR_TYPE_VIEW_STATE);
  XrView views[2] = {xrStruct<XrView>(XR_TYPE_VIEW), xrStruct<XrView>(XR_TYPE_VIEW)};
};

struct SessionSeen {
  std::vector<XrSessionState> states;
  std::vector<FrameSeen> frames;
};

struct AppOptions {
  bool depth = false;  // a depth swapchain per eye, submitted with XrCompositionLayerDepthInfoKHR
  bool quad = false;   // a quad layer besides the projection
};

// The clear colours: the left eye blue on an sRGB swapchain (0 and 1 encode unchanged), the right
// eye red on a BGRA swapchain (the PNG must come back swizzled) with the frame in its green.
inline constexpr VkFormat kLeftFormat = VK_FORMAT_R8G8B8A8_SRGB;
inline constexpr VkFormat kRightFormat = VK_FORMAT_B8G8R8A8_UNORM;
inline float greenOfFrame(std::size_t frame) {
  return static_cast<float>(frame * 40) / 255.0f;
}

class HeadsetApp {
 public:
  explicit HeadsetApp(std::vector<std::string>* validation_messages) : messages_(validation_messages) {}

  ~HeadsetApp() {
    for (XrSwapchain swapchain : swapchains_) xrDestroySwapchain(swapchain);
    if (session_ != XR_NULL_HANDLE) xrDestroySession(session_);
    if (command_pool_ != VK_NULL_HANDLE) vkDestroyCommandPool(device_, command_pool_, nullptr);
    if (fence_ != VK_NULL_HANDLE) vkDestroyFence(device_, fence_, nullptr);
    if (device_ != VK_NULL_HANDLE) vkDestroyDevice(device_, nullptr);
    if (messenger_ != VK_NULL_HANDLE) {
      const auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
          vkGetInstanceProcAddr(vk_instance_, "vkDestroyDebugUtilsMessengerEXT"));
      destroy(vk_instance_, messenger_, nullptr);
    }
    if (vk_instance_ != VK_NULL_HANDLE) vkDestroyInstance(vk_instance_, nullptr);
    if (instance_ != XR_NULL_HANDLE) xrDestroyInstance(instance_);
  }
  HeadsetApp(const HeadsetApp&) = delete;
  HeadsetApp& operator=(const HeadsetApp&) = delete;

  XrInstance instance() const { return instance_; }
  XrSession session() const { return session_; }

  void createInstance(bool depth_extension) {
    std::vector<const char*> extensions{XR_KHR_VULKAN_ENABLE2_EXTENSION_NAME};
    if (depth_extension) extensions.push_back(XR_KHR_COMPOSITION_LAYER_DEPTH_EXTENSION_NAME);
    auto create = xrStruct<XrInstanceCreateInfo>(XR_TYPE_INSTANCE_CREATE_INFO);
    std::snprintf(create.applicationInfo.applicationName, XR_MAX_APPLICATION_NAME_SIZE, "%s", "plumb_xr_headset_tests");
    create.applicationInfo.apiVersion = XR_CURRENT_API_VERSION;
    create.enabledExtensionCount = static_cast<std::uint32_t>(extensions.size());
    create.enabledExtensionNames = extensions.data();
    check(xrCreateInstance(&create, &instance_), "xrCreateInstance");
    auto system = xrStruct<XrSystemGetInfo>(XR_TYPE_SYSTEM_GET_INFO);
    system.formFactor = XR_FORM_FACTOR_HEAD_MOUNTED_DISPLAY;
    check(xrGetSystem(instance_, &system, &system_id_), "xrGetSystem");
  }

  void queryGraphicsRequirements() {
    auto requirements = xrStruct<XrGraphicsRequirementsVulkan2KHR>(XR_TYPE_GRAPHICS_REQUIREMENTS_VULKAN2_KHR);
    check(xrFunction<PFN_xrGetVulkanGraphicsRequirements2KHR>(instance_, "xrGetVulkanGraphicsRequirements2KHR")(
              instance_, system_id_, &requirements),
          "xrGetVulkanGraphicsRequirements2KHR");
  }

  // The Vulkan instance (validation on, a messenger recording warnings and errors) and device,
  // both through the runtime.
  void createVulkan() {
    auto application = vkStruct<VkApplicationInfo>(VK_STRUCTURE_TYPE_APPLICATION_INFO);
    application.pApplicationName = "plumb_xr_headset_tests";
    application.apiVersion = VK_API_VERSION_1_1;
    const char* layers[] = {"VK_LAYER_KHRONOS_validation"};
    const char* extensions[] = {VK_EXT_DEBUG_UTILS_EXTENSION_NAME};
    auto messenger =
        vkStruct<VkDebugUtilsMessengerCreateInfoEXT>(VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT);
    messenger.messageSeverity =
        VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
    messenger.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT |
                            VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                            VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
    messenger.pfnUserCallback = &HeadsetApp::onValidationMessage;
    messenger.pUserData = messages_;
    auto instance_info = vkStruct<VkInstanceCreateInfo>(VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO);
    instance_info.pNext = &messenger;  // also reports what happens in vkCreateInstance and vkDestroyInstance
    instance_info.pApplicationInfo = &application;
    instance_info.enabledLayerCount = 1;
    instance_info.ppEnabledLayerNames = layers;
    instance_info.enabledExtensionCount = 1;
    instance_info.ppEnabledExtensionNames = extensions;
    auto xr_instance_info = xrStruct<XrVulkanInstanceCreateInfoKHR>(XR_TYPE_VULKAN_INSTANCE_CREATE_INFO_KHR);
    xr_instance_info.systemId = system_id_;
    xr_instance_info.pfnGetInstanceProcAddr = &vkGetInstanceProcAddr;
    xr_instance_info.vulkanCreateInfo = &instance_info;
    VkResult vulkan_result = VK_ERROR_UNKNOWN;
    check(xrFunction<PFN_xrCreateVulkanInstanceKHR>(instance_, "xrCreateVulkanInstanceKHR")(
              instance_, &xr_instance_info, &vk_instance_, &vulkan_result),
          "xrCreateVulkanInstanceKHR");
    checkVk(vulkan_result, "vkCreateInstance through xrCreateVulkanInstanceKHR");
    const auto create_messenger = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(vk_instance_, "vkCreateDebugUtilsMessengerEXT"));
    checkVk(create_messenger(vk_instance_, &messenger, nullptr, &messenger_), "vkCreateDebugUtilsMessengerEXT");

    auto device_get = xrStruct<XrVulkanGraphicsDeviceGetInfoKHR>(XR_TYPE_VULKAN_GRAPHICS_DEVICE_GET_INFO_KHR);
    device_get.systemId = system_id_;
    device_get.vulkanInstance = vk_instance_;
    check(xrFunction<PFN_xrGetVulkanGraphicsDevice2KHR>(instance_, "xrGetVulkanGraphicsDevice2KHR")(
              instance_, &device_get, &physical_device_),
          "xrGetVulkanGraphicsDevice2KHR");
    std::uint32_t family_count = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(physical_device_, &family_count, nullptr);
    std::vector<VkQueueFamilyProperties> families(family_count);
    vkGetPhysicalDeviceQueueFamilyProperties(physical_device_, &family_count, families.data());
    queue_family_ = family_count;
    for (std::uint32_t i = 0; i < family_count; ++i) {
      if ((families[i].queueFlags & VK_QUEUE_GRAPHICS_BIT) != 0 && queue_family_ == family_count) queue_family_ = i;
    }
    if (queue_family_ == family_count) throw std::runtime_error("the headset's device has no graphics queue");

    const float priority = 1.0f;
    auto queue_info = vkStruct<VkDeviceQueueCreateInfo>(VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO);
    queue_info.queueFamilyIndex = queue_family_;
    queue_info.queueCount = 1;
    queue_info.pQueuePriorities = &priority;
    auto device_info = vkStruct<VkDeviceCreateInfo>(VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO);
    device_info.queueCreateInfoCount = 1;
    device_info.pQueueCreateInfos = &queue_info;
    auto xr_device_info = xrStruct<XrVulkanDeviceCreateInfoKHR>(XR_TYPE_VULKAN_DEVICE_CREATE_INFO_KHR);
    xr_device_info.systemId = system_id_;
    xr_device_info.pfnGetInstanceProcAddr = &vkGetInstanceProcAddr;
    xr_device_info.vulkanPhysicalDevice = physical_device_;
    xr_device_info.vulkanCreateInfo = &device_info;
    check(xrFunction<PFN_xrCreateVulkanDeviceKHR>(instance_, "xrCreateVulkanDeviceKHR")(instance_, &xr_device_info,
                                                                                        &device_, &vulkan_result),
          "xrCreateVulkanDeviceKHR");
    checkVk(vulkan_result, "vkCreateDevice through xrCreateVulkanDeviceKHR");
    vkGetDeviceQueue(device_, queue_family_, 0, &queue_);

    auto pool_info = vkStruct<VkCommandPoolCreateInfo>(VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO);
    pool_info.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
    pool_info.queueFamilyIndex = queue_family_;
    checkVk(vkCreateCommandPool(device_, &pool_info, nullptr, &command_pool_), "vkCreateCommandPool");
    auto buffer_info = vkStruct<VkCommandBufferAllocateInfo>(VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO);
    buffer_info.commandPool = command_pool_;
    buffer_info.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    buffer_info.commandBufferCount = 1;
    checkVk(vkAllocateCommandBuffers(device_, &buffer_info, &command_buffer_), "vkAllocateCommandBuffers");
    auto fence_info = vkStruct<VkFenceCreateInfo>(VK_STRUCTURE_TYPE_FENCE_CREATE_INFO);
    checkVk(vkCreateFence(device_, &fence_info, nullptr, &fence_), "vkCreateFence");
  }

  XrResult tryCreateSession() {
    auto binding = xrStruct<XrGraphicsBindingVulkan2KHR>(XR_TYPE_GRAPHICS_BINDING_VULKAN2_KHR);
    binding.instance = vk_instance_;
    binding.physicalDevice = physical_device_;
    binding.device = device_;
    binding.queueFamilyIndex = queue_family_;
    binding.queueIndex = 0;
    auto create = xrStruct<XrSessionCreateInfo>(XR_TYPE_SESSION_CREATE_INFO);
    create.next = &binding;
    create.systemId = system_id_;
    return xrCreateSession(instance_, &create, &session_);
  }

  // The LOCAL space, a right-hand trigger (float) and aim pose, their bindings for the touch
  // controller profile and a few others, attached to the session.
  void createSpacesAndActions() {
    auto local = xrStruct<XrReferenceSpaceCreateInfo>(XR_TYPE_REFERENCE_SPACE_CREATE_INFO);
    local.referenceSpaceType = XR_REFERENCE_SPACE_TYPE_LOCAL;
    local.poseInReferenceSpace.orientation.w = 1;
    check(xrCreateReferenceSpace(session_, &local, &local_space_), "xrCreateReferenceSpace");

    auto set_info = xrStruct<XrActionSetCreateInfo>(XR_TYPE_ACTION_SET_CREATE_INFO);
    std::snprintf(set_info.actionSetName, XR_MAX_ACTION_SET_NAME_SIZE, "%s", "viewer");
    std::snprintf(set_info.localizedActionSetName, XR_MAX_LOCALIZED_ACTION_SET_NAME_SIZE, "%s", "Viewer");
    check(xrCreateActionSet(instance_, &set_info, &action_set_), "xrCreateActionSet");
    check(xrStringToPath(instance_, "/user/hand/right", &right_hand_), "xrStringToPath");
    trigger_ = createAction(XR_ACTION_TYPE_FLOAT_INPUT, "trigger", "Trigger");
    aim_ = createAction(XR_ACTION_TYPE_POSE_INPUT, "aim", "Aim");

    suggest("/interaction_profiles/oculus/touch_controller",
            {{trigger_, "/user/hand/right/input/trigger/value"}, {aim_, "/user/hand/right/input/aim/pose"}});
    // A profile the script does not hold: its bindings must stay inactive.
    suggest("/interaction_profiles/khr/simple_controller", {{trigger_, "/user/hand/left/input/select/click"}});

    auto aim_space = xrStruct<XrActionSpaceCreateInfo>(XR_TYPE_ACTION_SPACE_CREATE_INFO);
    aim_space.action = aim_;
    aim_space.subactionPath = right_hand_;
    aim_space.poseInActionSpace.orientation.w = 1;
    check(xrCreateActionSpace(session_, &aim_space, &aim_space_), "xrCreateActionSpace");
    auto attach = xrStruct<XrSessionActionSetsAttachInfo>(XR_TYPE_SESSION_ACTION_SETS_ATTACH_INFO);
    attach.countActionSets = 1;
    attach.actionSets = &action_set_;
    check(xrAttachSessionActionSets(session_, &attach), "xrAttachSessionActionSets");
  }

  // One swapchain per eye (kLeftFormat, kRightFormat), with the options' depth and quad ones.
  void createSwapchains(const AppOptions& options) {
    options_ = options;
    eye_colour_[0] = createSwapchain(kLeftFormat, kEyeWidthPx, kEyeHeightPx);
    eye_colour_[1] = createSwapchain(kRightFormat, kEyeWidthPx, kEyeHeightPx);
    if (options.depth) {
      for (Target& depth : eye_depth_) depth = createSwapchain(VK_FORMAT_D32_SFLOAT, kEyeWidthPx, kEyeHeightPx);
    }
    if (options.quad) quad_ = createSwapchain(VK_FORMAT_R8G8B8A8_UNORM, kQuadWidthPx, kQuadHeightPx);
  }

  // The application's loop: events, then a frame while running, until EXITING or LOSS_PENDING.
  SessionSeen run() {
    SessionSeen seen;
    bool running = false;
    for (int iteration = 0; iteration < kMaxIterations; ++iteration) {
      auto event = xrStruct<XrEventDataBuffer>(XR_TYPE_EVENT_DATA_BUFFER);
      while (xrPollEvent(instance_, &event) == XR_SUCCESS) {
        if (event.type == XR_TYPE_EVENT_DATA_SESSION_STATE_CHANGED) {
          const auto& changed = *reinterpret_cast<const XrEventDataSessionStateChanged*>(&event);
          seen.states.push_back(changed.state);
          if (changed.state == XR_SESSION_STATE_READY) {
            auto begin = xrStruct<XrSessionBeginInfo>(XR_TYPE_SESSION_BEGIN_INFO);
            begin.primaryViewConfigurationType = XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO;
            check(xrBeginSession(session_, &begin), "xrBeginSession");
            running = true;
          } else if (changed.state == XR_SESSION_STATE_STOPPING) {
            check(xrEndSession(session_), "xrEndSession");
            running = false;
          } else if (changed.state == XR_SESSION_STATE_EXITING || changed.state == XR_SESSION_STATE_LOSS_PENDING) {
            return seen;
          }
        }
        event = xrStruct<XrEventDataBuffer>(XR_TYPE_EVENT_DATA_BUFFER);
      }
      if (running) seen.frames.push_back(runFrame(seen.frames.size()));
    }
    throw std::runtime_error("the session did not end within " + std::to_string(kMaxIterations) + " iterations");
  }

 private:
  static constexpr int kMaxIterations = 100;
  static constexpr std::uint32_t kQuadWidthPx = 32, kQuadHeightPx = 16;

  struct Target {
    XrSwapchain swapchain = XR_NULL_HANDLE;
    std::vector<XrSwapchainImageVulkan2KHR> images;
    VkFormat format = VK_FORMAT_UNDEFINED;
    std::uint32_t acquired = 0;
  };

  static VKAPI_ATTR VkBool32 VKAPI_CALL onValidationMessage(VkDebugUtilsMessageSeverityFlagBitsEXT,
                                                            VkDebugUtilsMessageTypeFlagsEXT,
                                                            const VkDebugUtilsMessengerCallbackDataEXT* data,
                                                            void* user_data) {
    static_cast<std::vector<std::string>*>(user_data)->push_back(data->pMessage);
    return VK_FALSE;
  }

  XrAction createAction(XrActionType type, const char* name, const char* localized_name) {
    auto info = xrStruct<XrActionCreateInfo>(XR_TYPE_ACTION_CREATE_INFO);
    info.actionType = type;
    std::snprintf(info.actionName, XR_MAX_ACTION_NAME_SIZE, "%s", name);
    std::snprintf(info.localizedActionName, XR_MAX_LOCALIZED_ACTION_NAME_SIZE, "%s", localized_name);
    info.countSubactionPaths = 1;
    info.subactionPaths = &right_hand_;
    XrAction action = XR_NULL_HANDLE;
    check(xrCreateAction(action_set_, &info, &action), "xrCreateAction");
    return action;
  }

  void suggest(const char* profile, const std::vector<std::pair<XrAction, const char*>>& bindings) {
    std::vector<XrActionSuggestedBinding> suggested;
    for (const auto& [action, path] : bindings) {
      XrPath binding = XR_NULL_PATH;
      check(xrStringToPath(instance_, path, &binding), "xrStringToPath");
      suggested.push_back({action, binding});
    }
    auto info = xrStruct<XrInteractionProfileSuggestedBinding>(XR_TYPE_INTERACTION_PROFILE_SUGGESTED_BINDING);
    check(xrStringToPath(instance_, profile, &info.interactionProfile), "xrStringToPath");
    info.countSuggestedBindings = static_cast<std::uint32_t>(suggested.size());
    info.suggestedBindings = suggested.data();
    check(xrSuggestInteractionProfileBindings(instance_, &info), "xrSuggestInteractionProfileBindings");
  }

  Target createSwapchain(VkFormat format, std::uint32_t width, std::uint32_t height) {
    const bool depth = format == VK_FORMAT_D32_SFLOAT;
    auto info = xrStruct<XrSwapchainCreateInfo>(XR_TYPE_SWAPCHAIN_CREATE_INFO);
    info.usageFlags = XR_SWAPCHAIN_USAGE_TRANSFER_DST_BIT | (depth ? XR_SWAPCHAIN_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT
                                                                   : XR_SWAPCHAIN_USAGE_COLOR_ATTACHMENT_BIT);
    info.format = format;
    info.sampleCount = 1;
    info.width = width;
    info.height = height;
    info.faceCount = 1;
    info.arraySize = 1;
    info.mipCount = 1;
    Target target;
    target.format = format;
    check(xrCreateSwapchain(session_, &info, &target.swapchain), "xrCreateSwapchain");
    swapchains_.push_back(target.swapchain);
    std::uint32_t count = 0;
    check(xrEnumerateSwapchainImages(target.swapchain, 0, &count, nullptr), "xrEnumerateSwapchainImages");
    target.images.assign(count, xrStruct<XrSwapchainImageVulkan2KHR>(XR_TYPE_SWAPCHAIN_IMAGE_VULKAN2_KHR));
    check(xrEnumerateSwapchainImages(target.swapchain, count, &count,
                                     reinterpret_cast<XrSwapchainImageBaseHeader*>(target.images.data())),
          "xrEnumerateSwapchainImages");
    return target;
  }

  void acquire(Target& target) {
    check(xrAcquireSwapchainImage(target.swapchain, nullptr, &target.acquired), "xrAcquireSwapchainImage");
    auto wait = xrStruct<XrSwapchainImageWaitInfo>(XR_TYPE_SWAPCHAIN_IMAGE_WAIT_INFO);
    wait.timeout = XR_INFINITE_DURATION;
    check(xrWaitSwapchainImage(target.swapchain, &wait), "xrWaitSwapchainImage");
  }

  // Handover layout -> TRANSFER_DST, clear, -> handover layout (XR_KHR_vulkan_enable2's layouts).
  void recordClear(const Target& target, const VkClearColorValue& colour) {
    const bool depth = target.format == VK_FORMAT_D32_SFLOAT;
    const VkImageLayout handover =
        depth ? VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL : VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
    const VkAccessFlags attachment_access =
        depth ? VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT : VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
    const VkPipelineStageFlags attachment_stage =
        depth ? VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT : VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
    const VkImageSubresourceRange range{
        depth ? VkImageAspectFlags{VK_IMAGE_ASPECT_DEPTH_BIT} : VkImageAspectFlags{VK_IMAGE_ASPECT_COLOR_BIT}, 0, 1, 0,
        1};
    auto barrier = vkStruct<VkImageMemoryBarrier>(VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER);
    barrier.srcAccessMask = attachment_access;
    barrier.dstAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
    barrier.oldLayout = handover;
    barrier.newLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
    barrier.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    barrier.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    barrier.image = target.images[target.acquired].image;
    barrier.subresourceRange = range;
    vkCmdPipelineBarrier(command_buffer_, attachment_stage, VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 0, nullptr, 0, nullptr,
                         1, &barrier);
    if (depth) {
      const VkClearDepthStencilValue clear{0.5f, 0};
      vkCmdClearDepthStencilImage(command_buffer_, barrier.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &clear, 1,
                                  &range);
    } else {
      vkCmdClearColorImage(command_buffer_, barrier.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &colour, 1, &range);
    }
    barrier.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
    barrier.dstAccessMask = attachment_access;
    barrier.oldLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
    barrier.newLayout = handover;
    vkCmdPipelineBarrier(command_buffer_, VK_PIPELINE_STAGE_TRANSFER_BIT, attachment_stage, 0, 0, nullptr, 0, nullptr,
                         1, &barrier);
  }

  void release(const Target& target) {
    auto release = xrStruct<XrSwapchainImageReleaseInfo>(XR_TYPE_SWAPCHAIN_IMAGE_RELEASE_INFO);
    check(xrReleaseSwapchainImage(target.swapchain, &release), "xrReleaseSwapchainImage");
  }

  // Each target acquired, cleared in one submission the application waits for, and released.
  void render(std::size_t frame) {
    std::vector<Target*> targets{&eye_colour_[0], &eye_colour_[1]};
    if (options_.depth) targets.insert(targets.end(), {&eye_depth_[0], &eye_depth_[1]});
    if (options_.quad) targets.push_back(&quad_);
    for (Target* target : targets) acquire(*target);
    auto begin = vkStruct<VkCommandBufferBeginInfo>(VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO);
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    checkVk(vkBeginCommandBuffer(command_buffer_, &begin), "vkBeginCommandBuffer");
    recordClear(eye_colour_[0], {{0.0f, 0.0f, 1.0f, 1.0f}});
    recordClear(eye_colour_[1], {{1.0f, greenOfFrame(frame), 0.0f, 1.0f}});
    if (options_.depth) {
      for (const Target& depth : eye_depth_) recordClear(depth, {});
    }
    if (options_.quad) recordClear(quad_, {{1.0f, 1.0f, 0.0f, 1.0f}});
    checkVk(vkEndCommandBuffer(command_buffer_), "vkEndCommandBuffer");
    auto submit = vkStruct<VkSubmitInfo>(VK_STRUCTURE_TYPE_SUBMIT_INFO);
    submit.commandBufferCount = 1;
    submit.pCommandBuffers = &command_buffer_;
    checkVk(vkResetFences(device_, 1, &fence_), "vkResetFences");
    checkVk(vkQueueSubmit(queue_, 1, &submit, fence_), "vkQueueSubmit");
    checkVk(vkWaitForFences(device_, 1, &fence_, VK_TRUE, UINT64_MAX), "vkWaitForFences");
    for (Target* target : targets) release(*target);
  }

  FrameSeen runFrame(std::size_t frame) {
    FrameSeen seen;
    auto state = xrStruct<XrFrameState>(XR_TYPE_FRAME_STATE);
    seen.wait_result = xrWaitFrame(session_, nullptr, &state);
    check(seen.wait_result, "xrWaitFrame");
    seen.display_time = state.predictedDisplayTime;
    seen.should_render = state.shouldRender;
    check(xrBeginFrame(session_, nullptr), "xrBeginFrame");

    const XrActiveActionSet active{action_set_, XR_NULL_PATH};
    auto sync = xrStruct<XrActionsSyncInfo>(XR_TYPE_ACTIONS_SYNC_INFO);
    sync.countActiveActionSets = 1;
    sync.activeActionSets = &active;
    seen.sync_result = xrSyncActions(session_, &sync);
    check(seen.sync_result, "xrSyncActions");
    auto get = xrStruct<XrActionStateGetInfo>(XR_TYPE_ACTION_STATE_GET_INFO);
    get.action = trigger_;
    get.subactionPath = right_hand_;
    check(xrGetActionStateFloat(session_, &get, &seen.trigger), "xrGetActionStateFloat");
    get.action = aim_;
    check(xrGetActionStatePose(session_, &get, &seen.aim), "xrGetActionStatePose");
    check(xrLocateSpace(aim_space_, local_space_, state.predictedDisplayTime, &seen.aim_location), "xrLocateSpace");

    auto locate = xrStruct<XrViewLocateInfo>(XR_TYPE_VIEW_LOCATE_INFO);
    locate.viewConfigurationType = XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO;
    locate.displayTime = state.predictedDisplayTime;
    locate.space = local_space_;
    std::uint32_t view_count = 0;
    check(xrLocateViews(session_, &locate, &seen.view_state, 2, &view_count, seen.views), "xrLocateViews");

    XrCompositionLayerProjectionView views[2];
    XrCompositionLayerDepthInfoKHR depth[2];
    for (std::uint32_t eye = 0; eye < 2; ++eye) {
      views[eye] = xrStruct<XrCompositionLayerProjectionView>(XR_TYPE_COMPOSITION_LAYER_PROJECTION_VIEW);
      depth[eye] = xrStruct<XrCompositionLayerDepthInfoKHR>(XR_TYPE_COMPOSITION_LAYER_DEPTH_INFO_KHR);
    }
    auto projection = xrStruct<XrCompositionLayerProjection>(XR_TYPE_COMPOSITION_LAYER_PROJECTION);
    auto quad = xrStruct<XrCompositionLayerQuad>(XR_TYPE_COMPOSITION_LAYER_QUAD);
    std::vector<const XrCompositionLayerBaseHeader*> layers;
    if (state.shouldRender) {
      render(frame);
      for (std::uint32_t eye = 0; eye < 2; ++eye) {
        views[eye].pose = seen.views[eye].pose;
        views[eye].fov = seen.views[eye].fov;
        views[eye].subImage = {eye_colour_[eye].swapchain, {{0, 0}, {kEyeWidthPx, kEyeHeightPx}}, 0};
        if (options_.depth) {
          depth[eye].subImage = {eye_depth_[eye].swapchain, {{0, 0}, {kEyeWidthPx, kEyeHeightPx}}, 0};
          depth[eye].minDepth = 0;
          depth[eye].maxDepth = 1;
          depth[eye].nearZ = 0.05f;
          depth[eye].farZ = 100;
          views[eye].next = &depth[eye];
        }
      }
      projection.space = local_space_;
      projection.viewCount = 2;
      projection.views = views;
      layers.push_back(reinterpret_cast<const XrCompositionLayerBaseHeader*>(&projection));
      if (options_.quad) {
        quad.space = local_space_;
        quad.eyeVisibility = XR_EYE_VISIBILITY_BOTH;
        quad.subImage = {quad_.swapchain, {{0, 0}, {kQuadWidthPx, kQuadHeightPx}}, 0};
        quad.pose = {{0, 0, 0, 1}, {0, 1.5f, -2}};
        quad.size = {1, 0.5f};
        layers.push_back(reinterpret_cast<const XrCompositionLayerBaseHeader*>(&quad));
      }
    }
    auto end = xrStruct<XrFrameEndInfo>(XR_TYPE_FRAME_END_INFO);
    end.displayTime = state.predictedDisplayTime;
    end.environmentBlendMode = XR_ENVIRONMENT_BLEND_MODE_OPAQUE;
    end.layerCount = static_cast<std::uint32_t>(layers.size());
    end.layers = layers.data();
    check(xrEndFrame(session_, &end), "xrEndFrame");
    return seen;
  }

  std::vector<std::string>* messages_;
  AppOptions options_;
  XrInstance instance_ = XR_NULL_HANDLE;
  XrSystemId system_id_ = XR_NULL_SYSTEM_ID;
  XrSession session_ = XR_NULL_HANDLE;
  XrSpace local_space_ = XR_NULL_HANDLE, aim_space_ = XR_NULL_HANDLE;
  XrActionSet action_set_ = XR_NULL_HANDLE;
  XrAction trigger_ = XR_NULL_HANDLE, aim_ = XR_NULL_HANDLE;
  XrPath right_hand_ = XR_NULL_PATH;
  std::vector<XrSwapchain> swapchains_;
  Target eye_colour_[2], eye_depth_[2], quad_;
  VkInstance vk_instance_ = VK_NULL_HANDLE;
  VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
  VkPhysicalDevice physical_device_ = VK_NULL_HANDLE;
  VkDevice device_ = VK_NULL_HANDLE;
  std::uint32_t queue_family_ = 0;
  VkQueue queue_ = VK_NULL_HANDLE;
  VkCommandPool command_pool_ = VK_NULL_HANDLE;
  VkCommandBuffer command_buffer_ = VK_NULL_HANDLE;
  VkFence fence_ = VK_NULL_HANDLE;
};

}  // namespace plumb::test
