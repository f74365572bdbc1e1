// The controllers' actions.
//
//   1. One action set "plumb" with an aim pose, a trigger, a squeeze, a thumbstick and two
//      buttons, each for both hands (subaction paths /user/hand/left and /user/hand/right).
//   2. Suggested bindings for three profiles; the runtime picks the one its controllers match.
//   3. Each frame: xrSyncActions, then each action's state per hand and the aim pose located
//      in the stage at the frame's display time.

#include "ui/xr/xr_input.h"

#include <cstring>
#include <string>
#include <utility>
#include <vector>

#include "ui/xr/xr_check.h"

namespace plumb::xr {
namespace {

XrPath path(XrInstance instance, const std::string& name) {
  XrPath result = XR_NULL_PATH;
  check(xrStringToPath(instance, name.c_str(), &result), "xrStringToPath " + name);
  return result;
}

XrAction createAction(XrActionSet set, const char* name, const char* localized, XrActionType type,
                      const std::array<XrPath, 2>& hands) {
  auto create = xrStruct<XrActionCreateInfo>(XR_TYPE_ACTION_CREATE_INFO);
  std::strncpy(create.actionName, name, XR_MAX_ACTION_NAME_SIZE - 1);
  std::strncpy(create.localizedActionName, localized, XR_MAX_LOCALIZED_ACTION_NAME_SIZE - 1);
  create.actionType = type;
  create.countSubactionPaths = static_cast<std::uint32_t>(hands.size());
  create.subactionPaths = hands.data();
  XrAction action = XR_NULL_HANDLE;
  check(xrCreateAction(set, &create, &action), std::string("xrCreateAction ") + name);
  return action;
}

}  // namespace

Pose toPose(const XrPosef& pose) {
  Pose result;
  result.position = {pose.position.x, pose.position.y, pose.position.z};
  result.orientation =
      Eigen::Quaterniond(pose.orientation.w, pose.orientation.x, pose.orientation.y, pose.orientation.z).normalized();
  return result;
}

Input::Input(XrInstance instance, XrSession session) : instance_(instance), session_(session) {
  hands_ = {path(instance, "/user/hand/left"), path(instance, "/user/hand/right")};
  auto set = xrStruct<XrActionSetCreateInfo>(XR_TYPE_ACTION_SET_CREATE_INFO);
  std::strncpy(set.actionSetName, "plumb", XR_MAX_ACTION_SET_NAME_SIZE - 1);
  std::strncpy(set.localizedActionSetName, "Plumb", XR_MAX_LOCALIZED_ACTION_SET_NAME_SIZE - 1);
  check(xrCreateActionSet(instance, &set, &set_), "xrCreateActionSet");
  try {
    aim_ = createAction(set_, "aim", "Aim", XR_ACTION_TYPE_POSE_INPUT, hands_);
    trigger_ = createAction(set_, "trigger", "Grow, pick", XR_ACTION_TYPE_FLOAT_INPUT, hands_);
    squeeze_ = createAction(set_, "squeeze", "Grab the model", XR_ACTION_TYPE_FLOAT_INPUT, hands_);
    thumbstick_ = createAction(set_, "thumbstick", "Move, turn", XR_ACTION_TYPE_VECTOR2F_INPUT, hands_);
    primary_ = createAction(set_, "primary", "Primary button", XR_ACTION_TYPE_BOOLEAN_INPUT, hands_);
    secondary_ = createAction(set_, "secondary", "Secondary button", XR_ACTION_TYPE_BOOLEAN_INPUT, hands_);

    // Each profile's bindings; a profile the runtime does not know is skipped, not fatal.
    using Bindings = std::vector<std::pair<XrAction, std::string>>;
    const auto both = [](XrAction action, const std::string& input) {
      return Bindings{{action, "/user/hand/left/input/" + input}, {action, "/user/hand/right/input/" + input}};
    };
    const auto join = [](std::initializer_list<Bindings> lists) {
      Bindings all;
      for (const Bindings& list : lists) all.insert(all.end(), list.begin(), list.end());
      return all;
    };
    const std::vector<std::pair<std::string, Bindings>> profiles{
        {"/interaction_profiles/oculus/touch_controller", join({both(aim_, "aim/pose"),
                                                                both(trigger_, "trigger/value"),
                                                                both(squeeze_, "squeeze/value"),
                                                                both(thumbstick_, "thumbstick"),
                                                                {{primary_, "/user/hand/left/input/x/click"},
                                                                 {primary_, "/user/hand/right/input/a/click"},
                                                                 {secondary_, "/user/hand/left/input/y/click"},
                                                                 {secondary_, "/user/hand/right/input/b/click"}}})},
        {"/interaction_profiles/valve/index_controller",
         join({both(aim_, "aim/pose"), both(trigger_, "trigger/value"), both(squeeze_, "squeeze/value"),
               both(thumbstick_, "thumbstick"), both(primary_, "a/click"), both(secondary_, "b/click")})},
        {"/interaction_profiles/khr/simple_controller",
         join({both(aim_, "aim/pose"), both(trigger_, "select/click"), both(primary_, "menu/click")})}};
    for (const auto& [profile, bindings] : profiles) {
      std::vector<XrActionSuggestedBinding> suggested;
      for (const auto& [action, input] : bindings) suggested.push_back({action, path(instance, input)});
      auto suggestion = xrStruct<XrInteractionProfileSuggestedBinding>(XR_TYPE_INTERACTION_PROFILE_SUGGESTED_BINDING);
      suggestion.interactionProfile = path(instance, profile);
      suggestion.countSuggestedBindings = static_cast<std::uint32_t>(suggested.size());
      suggestion.suggestedBindings = suggested.data();
      const XrResult result = xrSuggestInteractionProfileBindings(instance, &suggestion);
      if (result != XR_ERROR_PATH_UNSUPPORTED) check(result, "xrSuggestInteractionProfileBindings " + profile);
    }

    for (int hand = 0; hand < 2; ++hand) {
      auto space = xrStruct<XrActionSpaceCreateInfo>(XR_TYPE_ACTION_SPACE_CREATE_INFO);
      space.action = aim_;
      space.subactionPath = hands_[static_cast<std::size_t>(hand)];
      space.poseInActionSpace.orientation.w = 1.0f;
      check(xrCreateActionSpace(session, &space, &aim_spaces_[static_cast<std::size_t>(hand)]), "xrCreateActionSpace");
    }
    auto attach = xrStruct<XrSessionActionSetsAttachInfo>(XR_TYPE_SESSION_ACTION_SETS_ATTACH_INFO);
    attach.countActionSets = 1;
    attach.actionSets = &set_;
    check(xrAttachSessionActionSets(session, &attach), "xrAttachSessionActionSets");
  } catch (...) {
    for (XrSpace space : aim_spaces_) {
      if (space != XR_NULL_HANDLE) xrDestroySpace(space);
    }
    xrDestroyActionSet(set_);  // and its actions
    throw;
  }
}

Input::~Input() {
  for (XrSpace space : aim_spaces_) {
    if (space != XR_NULL_HANDLE) xrDestroySpace(space);
  }
  xrDestroyActionSet(set_);
}

void Input::sync(XrSpace stage, XrTime time, bool focused) {
  controllers_ = {};
  if (!focused) return;  // xrSyncActions would answer XR_SESSION_NOT_FOCUSED: no input
  XrActiveActionSet active{set_, XR_NULL_PATH};
  auto sync = xrStruct<XrActionsSyncInfo>(XR_TYPE_ACTIONS_SYNC_INFO);
  sync.countActiveActionSets = 1;
  sync.activeActionSets = &active;
  if (check(xrSyncActions(session_, &sync), "xrSyncActions") == XR_SESSION_NOT_FOCUSED) return;

  for (std::size_t hand = 0; hand < 2; ++hand) {
    Controller& controller = controllers_[hand];
    auto get = xrStruct<XrActionStateGetInfo>(XR_TYPE_ACTION_STATE_GET_INFO);
    get.subactionPath = hands_[hand];

    get.action = aim_;
    auto pose = xrStruct<XrActionStatePose>(XR_TYPE_ACTION_STATE_POSE);
    check(xrGetActionStatePose(session_, &get, &pose), "xrGetActionStatePose");
    controller.active = pose.isActive == XR_TRUE;
    if (!controller.active) continue;
    auto location = xrStruct<XrSpaceLocation>(XR_TYPE_SPACE_LOCATION);
    check(xrLocateSpace(aim_spaces_[hand], stage, time, &location), "xrLocateSpace (aim)");
    const XrSpaceLocationFlags valid = XR_SPACE_LOCATION_POSITION_VALID_BIT | XR_SPACE_LOCATION_ORIENTATION_VALID_BIT;
    controller.aim_valid = (location.locationFlags & valid) == valid;
    if (controller.aim_valid) controller.aim = toPose(location.pose);

    const auto readFloat = [&](XrAction action) {
      get.action = action;
      auto state = xrStruct<XrActionStateFloat>(XR_TYPE_ACTION_STATE_FLOAT);
      check(xrGetActionStateFloat(session_, &get, &state), "xrGetActionStateFloat");
      return state.isActive == XR_TRUE ? state.currentState : 0.0f;
    };
    const auto readBoolean = [&](XrAction action) {
      get.action = action;
      auto state = xrStruct<XrActionStateBoolean>(XR_TYPE_ACTION_STATE_BOOLEAN);
      check(xrGetActionStateBoolean(session_, &get, &state), "xrGetActionStateBoolean");
      return state.isActive == XR_TRUE && state.currentState == XR_TRUE;
    };
    controller.trigger = readFloat(trigger_);
    controller.squeeze = readFloat(squeeze_);
    get.action = thumbstick_;
    auto stick = xrStruct<XrActionStateVector2f>(XR_TYPE_ACTION_STATE_VECTOR2F);
    check(xrGetActionStateVector2f(session_, &get, &stick), "xrGetActionStateVector2f");
    if (stick.isActive == XR_TRUE) controller.thumbstick = {stick.currentState.x, stick.currentState.y};
    controller.primary = readBoolean(primary_);
    controller.secondary = readBoolean(secondary_);
  }
}

}  // namespace plumb::xr
