// Reading the controllers (OpenXR 1.0 specification, chapter 11 "Input and Haptics": sections
// "Input Action State Synchronization", "Reading Input Action State", "Bound Sources", "Output
// Actions and Haptics").
//
// xrSyncActions samples the script's controllers on the current frame (the last xrWaitFrame's):
//   1. Outside FOCUSED every action is inactive, and the call returns XR_SESSION_NOT_FOCUSED.
//   2. An action is active for a hand when its set is among the active sets for that hand, the hand
//      is present in the script, and a binding suggested for the script's profile reads that
//      hand's input in a way the action's type accepts.
//   3. Several bindings combine as the specification says: booleans OR, floats the largest
//      magnitude, vectors the longest; the combined source (subactionPath XR_NULL_PATH) combines the
//      hands the same way.
//   4. changedSinceLastSync compares with the previous sync's value while active in both;
//      lastChangeTime is the frame's display time when the value changed or became active.
// Haptics are accepted and go nowhere.

#include <cmath>
#include <string>
#include <vector>

#include "tests/support/xr_headset/action_bindings.h"
#include "tests/support/xr_headset/entry_points.h"
#include "tests/support/xr_headset/runtime_state.h"

namespace plumb::xr_headset {
namespace {

bool acceptsHand(const Action& action, Hand hand) {
  if (action.subaction_hands.empty()) return true;
  for (Hand listed : action.subaction_hands) {
    if (listed == hand) return true;
  }
  return false;
}

float vectorLength(const XrVector2f& v) {
  return std::sqrt(v.x * v.x + v.y * v.y);
}

// Folds `reading` into `into` (step 3).
void combine(SampledInput& into, const SampledInput& reading, XrActionType type) {
  if (!reading.active) return;
  if (!into.active) {
    into = reading;
    return;
  }
  switch (type) {
    case XR_ACTION_TYPE_BOOLEAN_INPUT:
      into.boolean = into.boolean || reading.boolean;
      break;
    case XR_ACTION_TYPE_FLOAT_INPUT:
      if (std::abs(reading.value) > std::abs(into.value)) into.value = reading.value;
      break;
    case XR_ACTION_TYPE_VECTOR2F_INPUT:
      if (vectorLength(reading.vector) > vectorLength(into.vector)) into.vector = reading.vector;
      break;
    default:
      break;  // poses: the first source found
  }
}

bool sameValue(const SampledInput& a, const SampledInput& b, XrActionType type) {
  switch (type) {
    case XR_ACTION_TYPE_BOOLEAN_INPUT:
      return a.boolean == b.boolean;
    case XR_ACTION_TYPE_FLOAT_INPUT:
      return a.value == b.value;
    case XR_ACTION_TYPE_VECTOR2F_INPUT:
      return a.vector.x == b.vector.x && a.vector.y == b.vector.y;
    default:
      return true;
  }
}

// Steps 2 to 4 for one action.
void sampleAction(std::uint64_t action_id, Action& action, const std::vector<SuggestedBinding>& bindings,
                  const bool (&hand_enabled)[kHandCount], const ScriptEntry& entry, XrTime now) {
  std::array<SampledInput, kHandCount + 1> next{};
  for (int h = 0; h < kHandCount; ++h) {
    const auto hand = static_cast<Hand>(h);
    const HandState& state = entry.hands[h];
    if (!hand_enabled[h] || !state.active || !acceptsHand(action, hand)) continue;
    for (const SuggestedBinding& binding : bindings) {
      if (binding.action != action_id) continue;
      const std::optional<BoundInput> bound = parseBindingPath(binding.path);
      if (!bound || bound->hand != hand) continue;
      const std::optional<InputReading> reading = readInput(state, bound->source, action.type);
      if (!reading) continue;
      SampledInput sampled;
      sampled.active = true;
      sampled.boolean = reading->boolean;
      sampled.value = reading->value;
      sampled.vector = reading->vector;
      sampled.grip_pose = reading->grip_pose;
      combine(next[static_cast<std::size_t>(h)], sampled, action.type);
    }
    combine(next[kCombinedSource], next[static_cast<std::size_t>(h)], action.type);
  }
  for (std::size_t source = 0; source < next.size(); ++source) {
    const SampledInput& before = action.sampled[source];
    SampledInput& after = next[source];
    if (!after.active) continue;
    const bool differs = !sameValue(before, after, action.type);
    after.changed = before.active && differs;
    after.last_change_time = (!before.active || differs) ? now : before.last_change_time;
  }
  action.sampled = next;
}

// The action `get_info` names, checked against the session, and its sampled source.
XrResult lookUpSampled(const char* function, const Session& session, const Instance& instance,
                       const XrActionStateGetInfo* get_info, XrActionType type, const SampledInput*& sampled) {
  if (get_info == nullptr || get_info->type != XR_TYPE_ACTION_STATE_GET_INFO) {
    return misuse(XR_ERROR_VALIDATION_FAILURE, function, "getInfo must have type XR_TYPE_ACTION_STATE_GET_INFO");
  }
  const Action* action = find(runtime().actions, idOf(get_info->action));
  const ActionSet* set = action == nullptr ? nullptr : find(runtime().action_sets, action->action_set);
  if (set == nullptr || set->instance != session.instance)
    return misuse(XR_ERROR_HANDLE_INVALID, function, "unknown XrAction");
  if (set->attached_session == 0 || find(runtime().sessions, set->attached_session) != &session) {
    return misuse(XR_ERROR_ACTIONSET_NOT_ATTACHED, function, "the action's set is not attached to this session");
  }
  if (action->type != type) return misuse(XR_ERROR_ACTION_TYPE_MISMATCH, function, "the action has another type");
  if (get_info->subactionPath == XR_NULL_PATH) {
    sampled = &action->sampled[kCombinedSource];
    return XR_SUCCESS;
  }
  if (pathString(instance, get_info->subactionPath) == nullptr) {
    return misuse(XR_ERROR_PATH_INVALID, function, "unknown subactionPath");
  }
  const std::optional<Hand> hand = handOfPath(instance, get_info->subactionPath);
  if (!hand || action->subaction_hands.empty() || !acceptsHand(*action, *hand)) {
    return misuse(XR_ERROR_PATH_UNSUPPORTED, function, "subactionPath is not one of the action's subaction paths");
  }
  sampled = &action->sampled[static_cast<std::size_t>(*hand)];
  return XR_SUCCESS;
}

// The session and the sampled state for the xrGetActionState* functions.
template <class State>
XrResult readState(const char* function, XrSession session, const XrActionStateGetInfo* get_info,
                   XrActionType action_type, XrStructureType state_type, State* state, const SampledInput*& sampled,
                   Session*& found) {
  Instance* owner = nullptr;
  if (const XrResult checked = lookUpSession(function, session, found, owner); XR_FAILED(checked)) return checked;
  if (state == nullptr || state->type != state_type) {
    return misuse(XR_ERROR_VALIDATION_FAILURE, function, "state has the wrong structure type");
  }
  return lookUpSampled(function, *found, *owner, get_info, action_type, sampled);
}

XrResult checkHaptic(const char* function, XrSession session, const XrHapticActionInfo* action_info, Session*& found) {
  Instance* owner = nullptr;
  if (const XrResult checked = lookUpSession(function, session, found, owner); XR_FAILED(checked)) return checked;
  if (action_info == nullptr || action_info->type != XR_TYPE_HAPTIC_ACTION_INFO) {
    return misuse(XR_ERROR_VALIDATION_FAILURE, function, "hapticActionInfo must have type XR_TYPE_HAPTIC_ACTION_INFO");
  }
  XrActionStateGetInfo as_get_info{};
  as_get_info.type = XR_TYPE_ACTION_STATE_GET_INFO;
  as_get_info.action = action_info->action;
  as_get_info.subactionPath = action_info->subactionPath;
  const SampledInput* sampled = nullptr;
  return lookUpSampled(function, *found, *owner, &as_get_info, XR_ACTION_TYPE_VIBRATION_OUTPUT, sampled);
}

// What a boolean, float and vector state share: active, changed since the last sync, and when.
template <typename State>
void fillChange(const SampledInput& sampled, State& state) {
  state.isActive = sampled.active ? XR_TRUE : XR_FALSE;
  state.changedSinceLastSync = sampled.changed ? XR_TRUE : XR_FALSE;
  state.lastChangeTime = sampled.active ? sampled.last_change_time : 0;
}

}  // namespace

XrResult XRAPI_CALL xrSyncActions(XrSession session, const XrActionsSyncInfo* sync_info) {
  constexpr const char* kSelf = "xrSyncActions";
  std::lock_guard lock(runtime().mutex);
  Session* found = nullptr;
  Instance* owner = nullptr;
  if (const XrResult checked = lookUpSession(kSelf, session, found, owner); XR_FAILED(checked)) return checked;
  if (sync_info == nullptr || sync_info->type != XR_TYPE_ACTIONS_SYNC_INFO) {
    return misuse(XR_ERROR_VALIDATION_FAILURE, kSelf, "syncInfo must have type XR_TYPE_ACTIONS_SYNC_INFO");
  }
  if (found->attached_action_sets.empty())
    return misuse(XR_ERROR_ACTIONSET_NOT_ATTACHED, kSelf, "attach the action sets first");
  if (sync_info->countActiveActionSets > 0 && sync_info->activeActionSets == nullptr) {
    return misuse(XR_ERROR_VALIDATION_FAILURE, kSelf, "null activeActionSets");
  }
  // Which hands each attached set is active for (step 2).
  std::map<std::uint64_t, std::array<bool, kHandCount>> enabled;
  const bool focused = found->state == XR_SESSION_STATE_FOCUSED;
  for (std::uint32_t i = 0; i < sync_info->countActiveActionSets; ++i) {
    const XrActiveActionSet& active = sync_info->activeActionSets[i];
    const ActionSet* set = find(runtime().action_sets, idOf(active.actionSet));
    if (set == nullptr || set->instance != found->instance)
      return misuse(XR_ERROR_HANDLE_INVALID, kSelf, "unknown XrActionSet");
    if (find(runtime().sessions, set->attached_session) != found) {
      return misuse(XR_ERROR_ACTIONSET_NOT_ATTACHED, kSelf, "an active action set is not attached to this session");
    }
    std::array<bool, kHandCount>& hands = enabled[idOf(active.actionSet)];
    if (active.subactionPath == XR_NULL_PATH) {
      hands = {true, true};
      continue;
    }
    if (pathString(*owner, active.subactionPath) == nullptr)
      return misuse(XR_ERROR_PATH_INVALID, kSelf, "unknown subactionPath");
    const std::optional<Hand> hand = handOfPath(*owner, active.subactionPath);
    if (!hand)
      return misuse(XR_ERROR_PATH_UNSUPPORTED, kSelf, "subactionPath must be /user/hand/left or /user/hand/right");
    hands[static_cast<std::size_t>(*hand)] = true;
  }

  const std::uint64_t frame = found->waited_frame < 0 ? 0 : static_cast<std::uint64_t>(found->waited_frame);
  const ScriptEntry& entry = owner->script.entryAt(frame);
  const XrTime now = displayTimeOf(owner->script, static_cast<std::int64_t>(frame));
  static const std::vector<SuggestedBinding> kNoBindings;
  const auto profile_bindings = owner->suggested_bindings.find(internPath(*owner, owner->script.profile));
  const std::vector<SuggestedBinding>& bindings =
      profile_bindings == owner->suggested_bindings.end() ? kNoBindings : profile_bindings->second;
  for (const auto& [action_id, action] : runtime().actions) {
    const ActionSet* set = find(runtime().action_sets, action->action_set);
    if (set == nullptr || find(runtime().sessions, set->attached_session) != found) continue;
    bool hands[kHandCount] = {false, false};
    if (focused) {
      if (const auto set_hands = enabled.find(action->action_set); set_hands != enabled.end()) {
        for (int h = 0; h < kHandCount; ++h) hands[h] = set_hands->second[static_cast<std::size_t>(h)];
      }
    }
    sampleAction(action_id, *action, bindings, hands, entry, now);
  }
  return focused ? sessionSuccess(*found) : XR_SESSION_NOT_FOCUSED;
}

XrResult XRAPI_CALL xrGetActionStateBoolean(XrSession session, const XrActionStateGetInfo* get_info,
                                            XrActionStateBoolean* state) {
  std::lock_guard lock(runtime().mutex);
  const SampledInput* sampled = nullptr;
  Session* found = nullptr;
  const XrResult result = readState("xrGetActionStateBoolean", session, get_info, XR_ACTION_TYPE_BOOLEAN_INPUT,
                                    XR_TYPE_ACTION_STATE_BOOLEAN, state, sampled, found);
  if (XR_FAILED(result)) return result;
  fillChange(*sampled, *state);
  state->currentState = sampled->active && sampled->boolean ? XR_TRUE : XR_FALSE;
  return sessionSuccess(*found);
}

XrResult XRAPI_CALL xrGetActionStateFloat(XrSession session, const XrActionStateGetInfo* get_info,
                                          XrActionStateFloat* state) {
  std::lock_guard lock(runtime().mutex);
  const SampledInput* sampled = nullptr;
  Session* found = nullptr;
  const XrResult result = readState("xrGetActionStateFloat", session, get_info, XR_ACTION_TYPE_FLOAT_INPUT,
                                    XR_TYPE_ACTION_STATE_FLOAT, state, sampled, found);
  if (XR_FAILED(result)) return result;
  fillChange(*sampled, *state);
  state->currentState = sampled->active ? sampled->value : 0;
  return sessionSuccess(*found);
}

XrResult XRAPI_CALL xrGetActionStateVector2f(XrSession session, const XrActionStateGetInfo* get_info,
                                             XrActionStateVector2f* state) {
  std::lock_guard lock(runtime().mutex);
  const SampledInput* sampled = nullptr;
  Session* found = nullptr;
  const XrResult result = readState("xrGetActionStateVector2f", session, get_info, XR_ACTION_TYPE_VECTOR2F_INPUT,
                                    XR_TYPE_ACTION_STATE_VECTOR2F, state, sampled, found);
  if (XR_FAILED(result)) return result;
  fillChange(*sampled, *state);
  state->currentState = sampled->active ? sampled->vector : XrVector2f{};
  return sessionSuccess(*found);
}

XrResult XRAPI_CALL xrGetActionStatePose(XrSession session, const XrActionStateGetInfo* get_info,
                                         XrActionStatePose* state) {
  std::lock_guard lock(runtime().mutex);
  const SampledInput* sampled = nullptr;
  Session* found = nullptr;
  const XrResult result = readState("xrGetActionStatePose", session, get_info, XR_ACTION_TYPE_POSE_INPUT,
                                    XR_TYPE_ACTION_STATE_POSE, state, sampled, found);
  if (XR_FAILED(result)) return result;
  state->isActive = sampled->active ? XR_TRUE : XR_FALSE;
  return sessionSuccess(*found);
}

XrResult XRAPI_CALL xrEnumerateBoundSourcesForAction(XrSession session,
                                                     const XrBoundSourcesForActionEnumerateInfo* enumerate_info,
                                                     uint32_t capacity, uint32_t* count_output, XrPath* sources) {
  constexpr const char* kSelf = "xrEnumerateBoundSourcesForAction";
  std::lock_guard lock(runtime().mutex);
  Session* found = nullptr;
  Instance* owner = nullptr;
  if (const XrResult checked = lookUpSession(kSelf, session, found, owner); XR_FAILED(checked)) return checked;
  if (enumerate_info == nullptr || enumerate_info->type != XR_TYPE_BOUND_SOURCES_FOR_ACTION_ENUMERATE_INFO) {
    return misuse(XR_ERROR_VALIDATION_FAILURE, kSelf,
                  "enumerateInfo must have type XR_TYPE_BOUND_SOURCES_FOR_ACTION_ENUMERATE_INFO");
  }
  const Action* action = find(runtime().actions, idOf(enumerate_info->action));
  const ActionSet* set = action == nullptr ? nullptr : find(runtime().action_sets, action->action_set);
  if (set == nullptr || set->instance != found->instance)
    return misuse(XR_ERROR_HANDLE_INVALID, kSelf, "unknown XrAction");
  if (find(runtime().sessions, set->attached_session) != found) {
    return misuse(XR_ERROR_ACTIONSET_NOT_ATTACHED, kSelf, "the action's set is not attached to this session");
  }
  if (capacity > 0 && sources == nullptr) return misuse(XR_ERROR_VALIDATION_FAILURE, kSelf, "null sources");
  // The bindings of the profile in use that read something this action accepts.
  std::vector<XrPath> bound;
  const auto profile_bindings = owner->suggested_bindings.find(internPath(*owner, owner->script.profile));
  if (profile_bindings != owner->suggested_bindings.end()) {
    const HandState any_hand;
    for (const SuggestedBinding& binding : profile_bindings->second) {
      if (binding.action != idOf(enumerate_info->action)) continue;
      const std::optional<BoundInput> input = parseBindingPath(binding.path);
      if (input && acceptsHand(*action, input->hand) && readInput(any_hand, input->source, action->type)) {
        bound.push_back(internPath(*owner, binding.path));
      }
    }
  }
  const XrResult result =
      fillArray(kSelf, capacity, count_output, static_cast<std::uint32_t>(bound.size()), [&](std::uint32_t i) {
        sources[i] = bound[i];
        return XR_SUCCESS;
      });
  return XR_FAILED(result) ? result : sessionSuccess(*found);
}

XrResult XRAPI_CALL xrApplyHapticFeedback(XrSession session, const XrHapticActionInfo* action_info,
                                          const XrHapticBaseHeader* haptic) {
  constexpr const char* kSelf = "xrApplyHapticFeedback";
  std::lock_guard lock(runtime().mutex);
  Session* found = nullptr;
  if (const XrResult checked = checkHaptic(kSelf, session, action_info, found); XR_FAILED(checked)) return checked;
  if (haptic == nullptr || haptic->type != XR_TYPE_HAPTIC_VIBRATION) {
    return misuse(XR_ERROR_VALIDATION_FAILURE, kSelf, "hapticFeedback must have type XR_TYPE_HAPTIC_VIBRATION");
  }
  return found->state == XR_SESSION_STATE_FOCUSED ? sessionSuccess(*found) : XR_SESSION_NOT_FOCUSED;
}

XrResult XRAPI_CALL xrStopHapticFeedback(XrSession session, const XrHapticActionInfo* action_info) {
  constexpr const char* kSelf = "xrStopHapticFeedback";
  std::lock_guard lock(runtime().mutex);
  Session* found = nullptr;
  if (const XrResult checked = checkHaptic(kSelf, session, action_info, found); XR_FAILED(checked)) return checked;
  return found->state == XR_SESSION_STATE_FOCUSED ? sessionSuccess(*found) : XR_SESSION_NOT_FOCUSED;
}

}  // namespace plumb::xr_headset
