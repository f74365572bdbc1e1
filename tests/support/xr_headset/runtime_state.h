#pragma once
// Everything the simulated headset holds between calls: the objects behind the handles it gives
// out (OpenXR 1.0 specification, section 2.9 "Handles": a destroyed parent destroys its children),
// the per-instance path table (chapter 6 "Path Tree and Semantic Paths"), the event queue (chapter
// 2 "Fundamentals", section "Event Polling") and the session state machine (chapter 9 "Session",
// section "Session States"). One mutex guards all of it: every entry point takes it first, and no
// entry point calls another.

#include <array>
#include <cstdint>
#include <deque>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <string_view>
#include <unordered_map>
#include <utility>
#include <vector>

#include "tests/support/xr_headset/headset_script.h"
#include "tests/support/xr_headset/swapchain_images.h"
#include "tests/support/xr_headset/vulkan_commands.h"

namespace plumb::xr_headset {

inline constexpr XrSystemId kSystemId = 1;
inline constexpr const char* kRuntimeName = "Plumb simulated headset";
inline constexpr std::uint32_t kMaxLayerCount = 16;
inline constexpr std::uint32_t kMaxSwapchainSizePx = 4096;
inline constexpr std::uint32_t kSwapchainImageCount = 3;

// Prints "simulated headset: <function>: <problem>" on stderr: every misuse the runtime detects,
// and every script event it cannot play, is reported the same way.
void report(const char* function, const std::string& problem);

// report(), then `result`.
XrResult misuse(XrResult result, const char* function, const std::string& problem);

struct SuggestedBinding {
  std::uint64_t action = 0;
  std::string path;  // "/user/hand/right/input/trigger/value"
};

struct Instance {
  HeadsetScript script;
  std::string output_folder;  // PLUMB_XR_HEADSET_OUT; empty: nothing is written
  bool vulkan_enable2 = false;
  bool depth_layers = false;  // XR_KHR_composition_layer_depth
  bool graphics_requirements_queried = false;
  // XrPath n names path_strings[n - 1].
  std::vector<std::string> path_strings;
  std::unordered_map<std::string, XrPath> path_ids;
  std::deque<XrEventDataBuffer> events;
  // What xrGetVulkanGraphicsDevice2KHR answered; sessions and devices must use this device.
  VkInstance vulkan_instance = VK_NULL_HANDLE;
  VkPhysicalDevice physical_device = VK_NULL_HANDLE;
  // Per interaction profile path, the bindings the last xrSuggestInteractionProfileBindings gave.
  std::map<XrPath, std::vector<SuggestedBinding>> suggested_bindings;
  std::uint64_t session = 0;  // the one session a headset has at a time; 0 when none
};

struct Session {
  std::uint64_t instance = 0;
  VulkanBinding vulkan;
  std::unique_ptr<OneShotCommands> commands;
  XrSessionState state = XR_SESSION_STATE_IDLE;
  bool running = false;  // between xrBeginSession and xrEndSession
  bool exiting = false;  // STOPPING was for good: xrEndSession leads to EXITING
  bool loss_pending = false;
  bool lost = false;
  bool frames_started = false;     // the first xrWaitFrame of this run happened
  std::int64_t waited_frame = -1;  // the script frame the last xrWaitFrame returned
  bool frame_waited = false;       // a waited frame not yet begun
  std::optional<std::uint64_t> begun_frame;
  std::vector<std::uint64_t> attached_action_sets;
};

struct Space {
  std::uint64_t session = 0;
  bool is_action_space = false;
  XrReferenceSpaceType reference_type = XR_REFERENCE_SPACE_TYPE_LOCAL;
  std::uint64_t action = 0;
  XrPath subaction_path = XR_NULL_PATH;
  Pose pose_in_space;  // poseInReferenceSpace or poseInActionSpace
};

struct ActionSet {
  std::uint64_t instance = 0;
  std::string name, localized_name;
  std::uint64_t attached_session = 0;  // 0 until xrAttachSessionActionSets
};

// One action's state from the last xrSyncActions, for one source.
struct SampledInput {
  bool active = false;
  bool boolean = false;
  float value = 0;
  XrVector2f vector{};
  bool changed = false;
  XrTime last_change_time = 0;
  bool grip_pose = false;  // a pose action's source: grip (true) or aim
};

// Sources of an action's state: each hand, and the two combined (subactionPath XR_NULL_PATH).
inline constexpr std::size_t kCombinedSource = kHandCount;

struct Action {
  std::uint64_t action_set = 0;
  std::string name, localized_name;
  XrActionType type = XR_ACTION_TYPE_BOOLEAN_INPUT;
  std::vector<Hand> subaction_hands;  // empty: no subaction paths
  std::array<SampledInput, kHandCount + 1> sampled;
};

struct Swapchain {
  std::uint64_t session = 0;
  SwapchainImageSpec spec;
  bool static_image = false;
  std::unique_ptr<SwapchainImages> images;
  std::uint32_t next_index = 0;
  std::uint32_t acquire_count = 0;
  std::deque<std::uint32_t> acquired;     // acquired, not yet waited, oldest first
  std::optional<std::uint32_t> waited;    // waited, not yet released
  std::optional<std::uint32_t> released;  // the last image released: what a layer shows
};

struct Runtime {
  Runtime() = default;
  // Runs when the loader unloads the library or the process exits. Objects the application never
  // destroyed keep their Vulkan objects: the device they belong to may be gone already.
  ~Runtime();
  Runtime(const Runtime&) = delete;
  Runtime& operator=(const Runtime&) = delete;

  std::mutex mutex;
  std::uint64_t next_id = 1;
  std::map<std::uint64_t, std::unique_ptr<Instance>> instances;
  std::map<std::uint64_t, std::unique_ptr<Session>> sessions;
  std::map<std::uint64_t, std::unique_ptr<Space>> spaces;
  std::map<std::uint64_t, std::unique_ptr<ActionSet>> action_sets;
  std::map<std::uint64_t, std::unique_ptr<Action>> actions;
  std::map<std::uint64_t, std::unique_ptr<Swapchain>> swapchains;
};

Runtime& runtime();

// Handles are the objects' ids, unique across all kinds for the library's lifetime.
template <class Handle>
std::uint64_t idOf(Handle handle) {
  return static_cast<std::uint64_t>(reinterpret_cast<std::uintptr_t>(handle));
}
template <class Handle>
Handle handleOf(std::uint64_t id) {
  return reinterpret_cast<Handle>(static_cast<std::uintptr_t>(id));
}

// The object `id` names in `table`, or null.
template <class Object>
Object* find(const std::map<std::uint64_t, std::unique_ptr<Object>>& table, std::uint64_t id) {
  const auto found = table.find(id);
  return found == table.end() ? nullptr : found->second.get();
}

// Stores `object` under a fresh id and returns the id.
template <class Object>
std::uint64_t store(std::map<std::uint64_t, std::unique_ptr<Object>>& table, std::unique_ptr<Object> object) {
  const std::uint64_t id = runtime().next_id++;
  table.emplace(id, std::move(object));
  return id;
}

// The session behind `handle` and its instance. XR_ERROR_HANDLE_INVALID when unknown,
// XR_ERROR_SESSION_LOST once the session is lost (both reported).
XrResult lookUpSession(const char* function, XrSession handle, Session*& session, Instance*& instance);

// What a successful call on the session returns: XR_SESSION_LOSS_PENDING while the loss is pending.
inline XrResult sessionSuccess(const Session& session) {
  return session.loss_pending ? XR_SESSION_LOSS_PENDING : XR_SUCCESS;
}

// Whether a pose's orientation is a unit quaternion, as the API requires (XR_ERROR_POSE_INVALID).
bool isValidPose(const XrPosef& pose);

// Destruction with the children (section 2.9): a session's spaces and swapchains, an action set's
// actions, an instance's sessions and action sets.
void destroySwapchain(std::uint64_t id);
void destroySession(std::uint64_t id);
void destroyActionSet(std::uint64_t id);
void destroyInstance(std::uint64_t id);

// Paths (chapter 6): whether `path` is a well-formed path string, and the interning.
bool isWellFormedPath(std::string_view path);
// A path element: lower-case letters, digits, '-', '_' and '.', not only dots (action and action
// set names follow the same rule).
bool isWellFormedPathElement(std::string_view element);
XrPath internPath(Instance& instance, const std::string& path);
// The path's string, or null for XR_NULL_PATH and values never given out.
const std::string* pathString(const Instance& instance, XrPath path);
// The hand a top-level path /user/hand/left or /user/hand/right names.
std::optional<Hand> handOfPath(const Instance& instance, XrPath path);

// Time: frame n is predicted for display at (n + 1) * the frame period.
XrTime displayTimeOf(const HeadsetScript& script, std::int64_t frame);
// The script frame whose display time is nearest `time` (frame 0 for times before it).
std::uint64_t frameAtTime(const HeadsetScript& script, XrTime time);
// The time events of the session carry: the last waited frame's display time.
XrTime sessionTime(const Instance& instance, const Session& session);

// Queues an XrEventDataSessionStateChanged and moves the session to `state`.
void changeState(Instance& instance, std::uint64_t session_id, Session& session, XrSessionState state);
// Steps the session down to STOPPING through the states in between (READY/VISIBLE/FOCUSED ->
// SYNCHRONIZED -> STOPPING), marking it as exiting. Nothing if it is already stopping or not running.
void stopSession(Instance& instance, std::uint64_t session_id, Session& session);

// Two-call idiom (section 2.11 "Buffer Size Parameters"): writes `count` to *count_output and,
// when capacity allows, the items through `write(i)`. XR_ERROR_SIZE_INSUFFICIENT when the capacity
// is non-zero but too small.
template <class Write>
XrResult fillArray(const char* function, std::uint32_t capacity, std::uint32_t* count_output, std::uint32_t count,
                   Write write) {
  if (count_output == nullptr) return misuse(XR_ERROR_VALIDATION_FAILURE, function, "the count output is null");
  *count_output = count;
  if (capacity == 0) return XR_SUCCESS;
  if (capacity < count) {
    return misuse(XR_ERROR_SIZE_INSUFFICIENT, function,
                  "capacity " + std::to_string(capacity) + " is less than " + std::to_string(count));
  }
  for (std::uint32_t i = 0; i < count; ++i) {
    const XrResult result = write(i);
    if (XR_FAILED(result)) return result;
  }
  return XR_SUCCESS;
}

// The first structure of type `type` in a next chain, or null.
const XrBaseInStructure* findInChain(const void* next, XrStructureType type);

}  // namespace plumb::xr_headset
