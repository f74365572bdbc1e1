// The simulated headset's shared state (runtime_state.h): object destruction with children
// (OpenXR 1.0 specification, section 2.9 "Handles"), well-formed paths (chapter 6, section
// "Well-Formed Path Strings"), display times (chapter 10, section "Display Timing") and the
// session state machine (chapter 9, section "Session States": the running states are left through
// SYNCHRONIZED, and events are queued per instance in the order the changes happen).

#include "tests/support/xr_headset/runtime_state.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>

namespace plumb::xr_headset {

void report(const char* function, const std::string& problem) {
  std::fprintf(stderr, "simulated headset: %s: %s\n", function, problem.c_str());
}

XrResult misuse(XrResult result, const char* function, const std::string& problem) {
  report(function, problem);
  return result;
}

Runtime::~Runtime() {
  for (auto& [id, swapchain] : swapchains) (void)swapchain->images.release();
  for (auto& [id, session] : sessions) (void)session->commands.release();
}

Runtime& runtime() {
  static Runtime state;
  return state;
}

XrResult lookUpSession(const char* function, XrSession handle, Session*& session, Instance*& instance) {
  session = find(runtime().sessions, idOf(handle));
  if (session == nullptr) return misuse(XR_ERROR_HANDLE_INVALID, function, "unknown XrSession");
  if (session->lost) return misuse(XR_ERROR_SESSION_LOST, function, "the session is lost: destroy it");
  instance = find(runtime().instances, session->instance);
  return XR_SUCCESS;
}

bool isValidPose(const XrPosef& pose) {
  const XrQuaternionf& q = pose.orientation;
  const float squared_length = q.x * q.x + q.y * q.y + q.z * q.z + q.w * q.w;
  return std::abs(squared_length - 1.0f) <= 0.01f && std::isfinite(pose.position.x) && std::isfinite(pose.position.y) &&
         std::isfinite(pose.position.z);
}

void destroySwapchain(std::uint64_t id) {
  runtime().swapchains.erase(id);
}

void destroySession(std::uint64_t id) {
  Runtime& state = runtime();
  Session* session = find(state.sessions, id);
  if (session == nullptr) return;
  std::erase_if(state.spaces, [&](const auto& entry) { return entry.second->session == id; });
  // Swapchains first: their destructors use the session's queue.
  std::erase_if(state.swapchains, [&](const auto& entry) { return entry.second->session == id; });
  for (auto& [set_id, set] : state.action_sets) {
    if (set->attached_session == id) set->attached_session = 0;
  }
  if (Instance* instance = find(state.instances, session->instance)) {
    if (instance->session == id) instance->session = 0;
    // Events about a destroyed session would name a handle the application no longer has.
    std::erase_if(instance->events, [&](const XrEventDataBuffer& event) {
      XrSession named = XR_NULL_HANDLE;
      if (event.type == XR_TYPE_EVENT_DATA_SESSION_STATE_CHANGED) {
        named = reinterpret_cast<const XrEventDataSessionStateChanged*>(&event)->session;
      } else if (event.type == XR_TYPE_EVENT_DATA_INTERACTION_PROFILE_CHANGED) {
        named = reinterpret_cast<const XrEventDataInteractionProfileChanged*>(&event)->session;
      }
      return idOf(named) == id;
    });
  }
  state.sessions.erase(id);
}

void destroyActionSet(std::uint64_t id) {
  Runtime& state = runtime();
  // Action spaces outlive their actions (they are the session's children): they become untracked.
  std::erase_if(state.actions, [&](const auto& entry) { return entry.second->action_set == id; });
  state.action_sets.erase(id);
}

void destroyInstance(std::uint64_t id) {
  Runtime& state = runtime();
  std::vector<std::uint64_t> sessions, sets;
  for (const auto& [session_id, session] : state.sessions) {
    if (session->instance == id) sessions.push_back(session_id);
  }
  for (const auto& [set_id, set] : state.action_sets) {
    if (set->instance == id) sets.push_back(set_id);
  }
  for (std::uint64_t session_id : sessions) destroySession(session_id);
  for (std::uint64_t set_id : sets) destroyActionSet(set_id);
  state.instances.erase(id);
}

bool isWellFormedPathElement(std::string_view element) {
  if (element.empty()) return false;
  bool only_dots = true;
  for (char c : element) {
    const bool allowed = (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '-' || c == '_' || c == '.';
    if (!allowed) return false;
    if (c != '.') only_dots = false;
  }
  return !only_dots;
}

bool isWellFormedPath(std::string_view path) {
  if (path.size() < 2 || path.size() >= XR_MAX_PATH_LENGTH || path.front() != '/') return false;
  std::size_t start = 1;
  while (start <= path.size()) {
    const std::size_t end = std::min(path.find('/', start), path.size());
    if (!isWellFormedPathElement(path.substr(start, end - start))) return false;
    start = end + 1;
  }
  return true;
}

XrPath internPath(Instance& instance, const std::string& path) {
  const auto found = instance.path_ids.find(path);
  if (found != instance.path_ids.end()) return found->second;
  instance.path_strings.push_back(path);
  const XrPath id = instance.path_strings.size();
  instance.path_ids.emplace(path, id);
  return id;
}

const std::string* pathString(const Instance& instance, XrPath path) {
  if (path == XR_NULL_PATH || path > instance.path_strings.size()) return nullptr;
  return &instance.path_strings[path - 1];
}

std::optional<Hand> handOfPath(const Instance& instance, XrPath path) {
  const std::string* name = pathString(instance, path);
  if (name == nullptr) return std::nullopt;
  if (*name == "/user/hand/left") return Hand::kLeft;
  if (*name == "/user/hand/right") return Hand::kRight;
  return std::nullopt;
}

XrTime displayTimeOf(const HeadsetScript& script, std::int64_t frame) {
  return (frame + 1) * script.framePeriodNs();
}

std::uint64_t frameAtTime(const HeadsetScript& script, XrTime time) {
  const double periods = static_cast<double>(time) / static_cast<double>(script.framePeriodNs());
  const auto nearest = std::llround(periods) - 1;
  return nearest < 0 ? 0 : static_cast<std::uint64_t>(nearest);
}

XrTime sessionTime(const Instance& instance, const Session& session) {
  // Before the first frame: the time the first frame will be displayed at.
  return displayTimeOf(instance.script, std::max<std::int64_t>(session.waited_frame, 0));
}

void changeState(Instance& instance, std::uint64_t session_id, Session& session, XrSessionState state) {
  session.state = state;
  XrEventDataSessionStateChanged changed{};
  changed.type = XR_TYPE_EVENT_DATA_SESSION_STATE_CHANGED;
  changed.session = handleOf<XrSession>(session_id);
  changed.state = state;
  changed.time = sessionTime(instance, session);
  XrEventDataBuffer event{};
  std::memcpy(&event, &changed, sizeof changed);
  instance.events.push_back(event);
}

void stopSession(Instance& instance, std::uint64_t session_id, Session& session) {
  if (!session.running || session.state == XR_SESSION_STATE_STOPPING || session.loss_pending) return;
  session.exiting = true;
  if (session.state == XR_SESSION_STATE_FOCUSED) changeState(instance, session_id, session, XR_SESSION_STATE_VISIBLE);
  if (session.state == XR_SESSION_STATE_VISIBLE || session.state == XR_SESSION_STATE_READY) {
    changeState(instance, session_id, session, XR_SESSION_STATE_SYNCHRONIZED);
  }
  changeState(instance, session_id, session, XR_SESSION_STATE_STOPPING);
}

const XrBaseInStructure* findInChain(const void* next, XrStructureType type) {
  for (auto* item = static_cast<const XrBaseInStructure*>(next); item != nullptr; item = item->next) {
    if (item->type == type) return item;
  }
  return nullptr;
}

}  // namespace plumb::xr_headset
