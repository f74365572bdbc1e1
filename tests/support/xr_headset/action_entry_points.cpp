// Action sets, actions, suggested bindings and their attachment to the session (OpenXR 1.0
// specification, chapter 11 "Input and Haptics": sections "Action Sets", "Creating Actions",
// "Suggested Bindings", "Current Interaction Profile"). Any interaction profile is accepted; the
// one in use is the script's "profile", and only the bindings suggested for it are active
// (action_state_entry_points.cpp).

#include <algorithm>
#include <cstring>
#include <string>

#include "tests/support/xr_headset/entry_points.h"
#include "tests/support/xr_headset/runtime_state.h"

namespace plumb::xr_headset {
namespace {

// Names of action sets and actions: well-formed path elements, unique where they live.
XrResult checkNames(const char* function, const char* name, const char* localized_name) {
  if (!isWellFormedPathElement(name)) {
    return misuse(XR_ERROR_PATH_FORMAT_INVALID, function,
                  std::string("'") + name + "' is not a valid name (lower-case letters, digits, '-', '_', '.')");
  }
  if (localized_name[0] == '\0')
    return misuse(XR_ERROR_LOCALIZED_NAME_INVALID, function, "the localized name is empty");
  return XR_SUCCESS;
}

void queueProfileChanged(Instance& instance, std::uint64_t session_id) {
  XrEventDataInteractionProfileChanged changed{};
  changed.type = XR_TYPE_EVENT_DATA_INTERACTION_PROFILE_CHANGED;
  changed.session = handleOf<XrSession>(session_id);
  XrEventDataBuffer event{};
  std::memcpy(&event, &changed, sizeof changed);
  instance.events.push_back(event);
}

}  // namespace

XrResult XRAPI_CALL xrCreateActionSet(XrInstance instance, const XrActionSetCreateInfo* create_info,
                                      XrActionSet* action_set) {
  constexpr const char* kSelf = "xrCreateActionSet";
  std::lock_guard lock(runtime().mutex);
  const std::uint64_t instance_id = idOf(instance);
  if (find(runtime().instances, instance_id) == nullptr)
    return misuse(XR_ERROR_HANDLE_INVALID, kSelf, "unknown XrInstance");
  if (create_info == nullptr || action_set == nullptr || create_info->type != XR_TYPE_ACTION_SET_CREATE_INFO) {
    return misuse(XR_ERROR_VALIDATION_FAILURE, kSelf, "createInfo must have type XR_TYPE_ACTION_SET_CREATE_INFO");
  }
  if (const XrResult named = checkNames(kSelf, create_info->actionSetName, create_info->localizedActionSetName);
      XR_FAILED(named)) {
    return named;
  }
  for (const auto& [id, set] : runtime().action_sets) {
    if (set->instance != instance_id) continue;
    if (set->name == create_info->actionSetName) {
      return misuse(XR_ERROR_NAME_DUPLICATED, kSelf, "an action set is named " + set->name + " already");
    }
    if (set->localized_name == create_info->localizedActionSetName) {
      return misuse(XR_ERROR_LOCALIZED_NAME_DUPLICATED, kSelf, "an action set has that localized name already");
    }
  }
  auto created = std::make_unique<ActionSet>();
  created->instance = instance_id;
  created->name = create_info->actionSetName;
  created->localized_name = create_info->localizedActionSetName;
  *action_set = handleOf<XrActionSet>(store(runtime().action_sets, std::move(created)));
  return XR_SUCCESS;
}

XrResult XRAPI_CALL xrDestroyActionSet(XrActionSet action_set) {
  std::lock_guard lock(runtime().mutex);
  if (find(runtime().action_sets, idOf(action_set)) == nullptr) {
    return misuse(XR_ERROR_HANDLE_INVALID, "xrDestroyActionSet", "unknown XrActionSet");
  }
  destroyActionSet(idOf(action_set));
  return XR_SUCCESS;
}

XrResult XRAPI_CALL xrCreateAction(XrActionSet action_set, const XrActionCreateInfo* create_info, XrAction* action) {
  constexpr const char* kSelf = "xrCreateAction";
  std::lock_guard lock(runtime().mutex);
  const std::uint64_t set_id = idOf(action_set);
  const ActionSet* set = find(runtime().action_sets, set_id);
  if (set == nullptr) return misuse(XR_ERROR_HANDLE_INVALID, kSelf, "unknown XrActionSet");
  const Instance* owner = find(runtime().instances, set->instance);
  if (create_info == nullptr || action == nullptr || create_info->type != XR_TYPE_ACTION_CREATE_INFO) {
    return misuse(XR_ERROR_VALIDATION_FAILURE, kSelf, "createInfo must have type XR_TYPE_ACTION_CREATE_INFO");
  }
  if (set->attached_session != 0) {
    return misuse(XR_ERROR_ACTIONSETS_ALREADY_ATTACHED, kSelf, "the action set is attached to a session already");
  }
  if (const XrResult named = checkNames(kSelf, create_info->actionName, create_info->localizedActionName);
      XR_FAILED(named)) {
    return named;
  }
  for (const auto& [id, existing] : runtime().actions) {
    if (existing->action_set != set_id) continue;
    if (existing->name == create_info->actionName) {
      return misuse(XR_ERROR_NAME_DUPLICATED, kSelf, "the set has an action named " + existing->name + " already");
    }
    if (existing->localized_name == create_info->localizedActionName) {
      return misuse(XR_ERROR_LOCALIZED_NAME_DUPLICATED, kSelf,
                    "the set has an action with that localized name already");
    }
  }
  switch (create_info->actionType) {
    case XR_ACTION_TYPE_BOOLEAN_INPUT:
    case XR_ACTION_TYPE_FLOAT_INPUT:
    case XR_ACTION_TYPE_VECTOR2F_INPUT:
    case XR_ACTION_TYPE_POSE_INPUT:
    case XR_ACTION_TYPE_VIBRATION_OUTPUT:
      break;
    default:
      return misuse(XR_ERROR_VALIDATION_FAILURE, kSelf, "unknown XrActionType");
  }
  if (create_info->countSubactionPaths > 0 && create_info->subactionPaths == nullptr) {
    return misuse(XR_ERROR_VALIDATION_FAILURE, kSelf, "null subactionPaths");
  }
  auto created = std::make_unique<Action>();
  created->action_set = set_id;
  created->name = create_info->actionName;
  created->localized_name = create_info->localizedActionName;
  created->type = create_info->actionType;
  for (std::uint32_t i = 0; i < create_info->countSubactionPaths; ++i) {
    const XrPath path = create_info->subactionPaths[i];
    if (pathString(*owner, path) == nullptr) return misuse(XR_ERROR_PATH_INVALID, kSelf, "unknown subaction path");
    const std::optional<Hand> hand = handOfPath(*owner, path);
    if (!hand) {
      return misuse(XR_ERROR_PATH_UNSUPPORTED, kSelf,
                    *pathString(*owner, path) + " is not a subaction path here (/user/hand/left, /user/hand/right)");
    }
    if (std::find(created->subaction_hands.begin(), created->subaction_hands.end(), *hand) !=
        created->subaction_hands.end()) {
      return misuse(XR_ERROR_PATH_UNSUPPORTED, kSelf, *pathString(*owner, path) + " is listed twice");
    }
    created->subaction_hands.push_back(*hand);
  }
  *action = handleOf<XrAction>(store(runtime().actions, std::move(created)));
  return XR_SUCCESS;
}

XrResult XRAPI_CALL xrDestroyAction(XrAction action) {
  std::lock_guard lock(runtime().mutex);
  if (runtime().actions.erase(idOf(action)) == 0)
    return misuse(XR_ERROR_HANDLE_INVALID, "xrDestroyAction", "unknown XrAction");
  return XR_SUCCESS;
}

XrResult XRAPI_CALL xrSuggestInteractionProfileBindings(XrInstance instance,
                                                        const XrInteractionProfileSuggestedBinding* suggested) {
  constexpr const char* kSelf = "xrSuggestInteractionProfileBindings";
  std::lock_guard lock(runtime().mutex);
  const std::uint64_t instance_id = idOf(instance);
  Instance* owner = find(runtime().instances, instance_id);
  if (owner == nullptr) return misuse(XR_ERROR_HANDLE_INVALID, kSelf, "unknown XrInstance");
  if (suggested == nullptr || suggested->type != XR_TYPE_INTERACTION_PROFILE_SUGGESTED_BINDING) {
    return misuse(XR_ERROR_VALIDATION_FAILURE, kSelf,
                  "suggestedBindings must have type XR_TYPE_INTERACTION_PROFILE_SUGGESTED_BINDING");
  }
  const std::string* profile = pathString(*owner, suggested->interactionProfile);
  if (profile == nullptr) return misuse(XR_ERROR_PATH_INVALID, kSelf, "unknown interactionProfile path");
  if (!profile->starts_with("/interaction_profiles/")) {
    return misuse(XR_ERROR_PATH_UNSUPPORTED, kSelf, *profile + " is not an interaction profile path");
  }
  if (suggested->countSuggestedBindings == 0 || suggested->suggestedBindings == nullptr) {
    return misuse(XR_ERROR_VALIDATION_FAILURE, kSelf, "no suggested bindings");
  }
  std::vector<SuggestedBinding> bindings;
  for (std::uint32_t i = 0; i < suggested->countSuggestedBindings; ++i) {
    const XrActionSuggestedBinding& binding = suggested->suggestedBindings[i];
    const Action* action = find(runtime().actions, idOf(binding.action));
    const ActionSet* set = action == nullptr ? nullptr : find(runtime().action_sets, action->action_set);
    if (set == nullptr || set->instance != instance_id)
      return misuse(XR_ERROR_HANDLE_INVALID, kSelf, "unknown XrAction");
    if (set->attached_session != 0) {
      return misuse(XR_ERROR_ACTIONSETS_ALREADY_ATTACHED, kSelf, "the action's set is attached to a session already");
    }
    const std::string* path = pathString(*owner, binding.binding);
    if (path == nullptr) return misuse(XR_ERROR_PATH_INVALID, kSelf, "unknown binding path");
    bindings.push_back({idOf(binding.action), *path});
  }
  // Each call replaces the profile's earlier suggestions (section "Suggested Bindings").
  owner->suggested_bindings[suggested->interactionProfile] = std::move(bindings);
  return XR_SUCCESS;
}

XrResult XRAPI_CALL xrAttachSessionActionSets(XrSession session, const XrSessionActionSetsAttachInfo* attach_info) {
  constexpr const char* kSelf = "xrAttachSessionActionSets";
  std::lock_guard lock(runtime().mutex);
  Session* found = nullptr;
  Instance* owner = nullptr;
  if (const XrResult checked = lookUpSession(kSelf, session, found, owner); XR_FAILED(checked)) return checked;
  if (attach_info == nullptr || attach_info->type != XR_TYPE_SESSION_ACTION_SETS_ATTACH_INFO) {
    return misuse(XR_ERROR_VALIDATION_FAILURE, kSelf,
                  "attachInfo must have type XR_TYPE_SESSION_ACTION_SETS_ATTACH_INFO");
  }
  if (!found->attached_action_sets.empty()) {
    return misuse(XR_ERROR_ACTIONSETS_ALREADY_ATTACHED, kSelf, "the session has action sets attached already");
  }
  if (attach_info->countActionSets == 0 || attach_info->actionSets == nullptr) {
    return misuse(XR_ERROR_VALIDATION_FAILURE, kSelf, "no action sets");
  }
  std::vector<ActionSet*> sets;
  for (std::uint32_t i = 0; i < attach_info->countActionSets; ++i) {
    ActionSet* set = find(runtime().action_sets, idOf(attach_info->actionSets[i]));
    if (set == nullptr || set->instance != found->instance)
      return misuse(XR_ERROR_HANDLE_INVALID, kSelf, "unknown XrActionSet");
    if (set->attached_session != 0) {
      return misuse(XR_ERROR_ACTIONSETS_ALREADY_ATTACHED, kSelf, "an action set is attached to a session already");
    }
    sets.push_back(set);
  }
  const std::uint64_t session_id = idOf(session);
  for (std::uint32_t i = 0; i < attach_info->countActionSets; ++i) {
    sets[i]->attached_session = session_id;
    found->attached_action_sets.push_back(idOf(attach_info->actionSets[i]));
  }
  // The script's controllers are held from the start: the profile becomes current now.
  queueProfileChanged(*owner, session_id);
  return sessionSuccess(*found);
}

XrResult XRAPI_CALL xrGetCurrentInteractionProfile(XrSession session, XrPath top_level_user_path,
                                                   XrInteractionProfileState* profile) {
  constexpr const char* kSelf = "xrGetCurrentInteractionProfile";
  std::lock_guard lock(runtime().mutex);
  Session* found = nullptr;
  Instance* owner = nullptr;
  if (const XrResult checked = lookUpSession(kSelf, session, found, owner); XR_FAILED(checked)) return checked;
  if (profile == nullptr || profile->type != XR_TYPE_INTERACTION_PROFILE_STATE) {
    return misuse(XR_ERROR_VALIDATION_FAILURE, kSelf,
                  "interactionProfile must have type XR_TYPE_INTERACTION_PROFILE_STATE");
  }
  if (found->attached_action_sets.empty()) {
    return misuse(XR_ERROR_ACTIONSET_NOT_ATTACHED, kSelf, "attach the action sets first");
  }
  const std::string* user_path = pathString(*owner, top_level_user_path);
  if (user_path == nullptr) return misuse(XR_ERROR_PATH_INVALID, kSelf, "unknown topLevelUserPath");
  if (handOfPath(*owner, top_level_user_path)) {
    profile->interactionProfile = internPath(*owner, owner->script.profile);
  } else if (user_path->starts_with("/user/")) {
    profile->interactionProfile = XR_NULL_PATH;  // a top-level path with nothing held there
  } else {
    return misuse(XR_ERROR_PATH_UNSUPPORTED, kSelf, *user_path + " is not a top-level user path");
  }
  return sessionSuccess(*found);
}

XrResult XRAPI_CALL xrGetInputSourceLocalizedName(XrSession session, const XrInputSourceLocalizedNameGetInfo* get_info,
                                                  uint32_t capacity, uint32_t* count_output, char* buffer) {
  constexpr const char* kSelf = "xrGetInputSourceLocalizedName";
  std::lock_guard lock(runtime().mutex);
  Session* found = nullptr;
  Instance* owner = nullptr;
  if (const XrResult checked = lookUpSession(kSelf, session, found, owner); XR_FAILED(checked)) return checked;
  if (get_info == nullptr || get_info->type != XR_TYPE_INPUT_SOURCE_LOCALIZED_NAME_GET_INFO) {
    return misuse(XR_ERROR_VALIDATION_FAILURE, kSelf,
                  "getInfo must have type XR_TYPE_INPUT_SOURCE_LOCALIZED_NAME_GET_INFO");
  }
  if (found->attached_action_sets.empty()) {
    return misuse(XR_ERROR_ACTIONSET_NOT_ATTACHED, kSelf, "attach the action sets first");
  }
  const std::string* source = pathString(*owner, get_info->sourcePath);
  if (source == nullptr) return misuse(XR_ERROR_PATH_INVALID, kSelf, "unknown sourcePath");
  if (capacity > 0 && buffer == nullptr) return misuse(XR_ERROR_VALIDATION_FAILURE, kSelf, "null buffer");
  // The simulated controllers' names are their paths.
  const auto size = static_cast<std::uint32_t>(source->size() + 1);
  const XrResult result = fillArray(kSelf, capacity, count_output, size, [&](std::uint32_t i) {
    buffer[i] = i < source->size() ? (*source)[i] : '\0';
    return XR_SUCCESS;
  });
  return XR_FAILED(result) ? result : sessionSuccess(*found);
}

}  // namespace plumb::xr_headset
