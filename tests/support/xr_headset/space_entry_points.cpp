// Space entry points of the simulated headset (OpenXR 1.0 specification, chapter 7 "Spaces":
// reference spaces VIEW, LOCAL and STAGE, where LOCAL and STAGE are both the script's space and
// VIEW is the head; action spaces; xrLocateSpace with every valid and tracked flag) and
// xrLocateViews (chapter 10 "Rendering", section "View and Projection State": the primary stereo
// pair, ipd apart, with the script's field of view).

#include <string>

#include "tests/support/xr_headset/entry_points.h"
#include "tests/support/xr_headset/runtime_state.h"
#include "tests/support/xr_headset/space_poses.h"

namespace plumb::xr_headset {
namespace {

constexpr XrReferenceSpaceType kReferenceSpaces[] = {XR_REFERENCE_SPACE_TYPE_VIEW, XR_REFERENCE_SPACE_TYPE_LOCAL,
                                                     XR_REFERENCE_SPACE_TYPE_STAGE};

constexpr XrSpaceLocationFlags kTracked =
    XR_SPACE_LOCATION_ORIENTATION_VALID_BIT | XR_SPACE_LOCATION_POSITION_VALID_BIT |
    XR_SPACE_LOCATION_ORIENTATION_TRACKED_BIT | XR_SPACE_LOCATION_POSITION_TRACKED_BIT;

constexpr XrViewStateFlags kViewTracked = XR_VIEW_STATE_ORIENTATION_VALID_BIT | XR_VIEW_STATE_POSITION_VALID_BIT |
                                          XR_VIEW_STATE_ORIENTATION_TRACKED_BIT | XR_VIEW_STATE_POSITION_TRACKED_BIT;

bool isOffered(XrReferenceSpaceType type) {
  for (XrReferenceSpaceType offered : kReferenceSpaces) {
    if (offered == type) return true;
  }
  return false;
}

XrFovf toXrFov(const FieldOfView& fov) {
  return {static_cast<float>(fov.left), static_cast<float>(fov.right), static_cast<float>(fov.up),
          static_cast<float>(fov.down)};
}

}  // namespace

XrResult XRAPI_CALL xrEnumerateReferenceSpaces(XrSession session, uint32_t capacity, uint32_t* count_output,
                                               XrReferenceSpaceType* spaces) {
  constexpr const char* kSelf = "xrEnumerateReferenceSpaces";
  std::lock_guard lock(runtime().mutex);
  Session* found = nullptr;
  Instance* owner = nullptr;
  if (const XrResult checked = lookUpSession(kSelf, session, found, owner); XR_FAILED(checked)) return checked;
  if (capacity > 0 && spaces == nullptr) return misuse(XR_ERROR_VALIDATION_FAILURE, kSelf, "null spaces");
  const XrResult result = fillArray(kSelf, capacity, count_output,
                                    static_cast<std::uint32_t>(std::size(kReferenceSpaces)), [&](std::uint32_t i) {
                                      spaces[i] = kReferenceSpaces[i];
                                      return XR_SUCCESS;
                                    });
  return XR_FAILED(result) ? result : sessionSuccess(*found);
}

XrResult XRAPI_CALL xrCreateReferenceSpace(XrSession session, const XrReferenceSpaceCreateInfo* create_info,
                                           XrSpace* space) {
  constexpr const char* kSelf = "xrCreateReferenceSpace";
  std::lock_guard lock(runtime().mutex);
  Session* found = nullptr;
  Instance* owner = nullptr;
  if (const XrResult checked = lookUpSession(kSelf, session, found, owner); XR_FAILED(checked)) return checked;
  if (create_info == nullptr || space == nullptr || create_info->type != XR_TYPE_REFERENCE_SPACE_CREATE_INFO) {
    return misuse(XR_ERROR_VALIDATION_FAILURE, kSelf, "createInfo must have type XR_TYPE_REFERENCE_SPACE_CREATE_INFO");
  }
  if (!isOffered(create_info->referenceSpaceType)) {
    return misuse(XR_ERROR_REFERENCE_SPACE_UNSUPPORTED, kSelf, "only VIEW, LOCAL and STAGE are offered");
  }
  if (!isValidPose(create_info->poseInReferenceSpace)) {
    return misuse(XR_ERROR_POSE_INVALID, kSelf, "poseInReferenceSpace's orientation is not a unit quaternion");
  }
  auto created = std::make_unique<Space>();
  created->session = idOf(session);
  created->reference_type = create_info->referenceSpaceType;
  created->pose_in_space = fromXr(create_info->poseInReferenceSpace);
  *space = handleOf<XrSpace>(store(runtime().spaces, std::move(created)));
  return sessionSuccess(*found);
}

XrResult XRAPI_CALL xrGetReferenceSpaceBoundsRect(XrSession session, XrReferenceSpaceType type, XrExtent2Df* bounds) {
  constexpr const char* kSelf = "xrGetReferenceSpaceBoundsRect";
  std::lock_guard lock(runtime().mutex);
  Session* found = nullptr;
  Instance* owner = nullptr;
  if (const XrResult checked = lookUpSession(kSelf, session, found, owner); XR_FAILED(checked)) return checked;
  if (!isOffered(type))
    return misuse(XR_ERROR_REFERENCE_SPACE_UNSUPPORTED, kSelf, "only VIEW, LOCAL and STAGE are offered");
  if (bounds == nullptr) return misuse(XR_ERROR_VALIDATION_FAILURE, kSelf, "null bounds");
  // The simulated room has no play area.
  *bounds = {0, 0};
  return XR_SPACE_BOUNDS_UNAVAILABLE;
}

XrResult XRAPI_CALL xrCreateActionSpace(XrSession session, const XrActionSpaceCreateInfo* create_info, XrSpace* space) {
  constexpr const char* kSelf = "xrCreateActionSpace";
  std::lock_guard lock(runtime().mutex);
  Session* found = nullptr;
  Instance* owner = nullptr;
  if (const XrResult checked = lookUpSession(kSelf, session, found, owner); XR_FAILED(checked)) return checked;
  if (create_info == nullptr || space == nullptr || create_info->type != XR_TYPE_ACTION_SPACE_CREATE_INFO) {
    return misuse(XR_ERROR_VALIDATION_FAILURE, kSelf, "createInfo must have type XR_TYPE_ACTION_SPACE_CREATE_INFO");
  }
  const Action* action = find(runtime().actions, idOf(create_info->action));
  const ActionSet* set = action == nullptr ? nullptr : find(runtime().action_sets, action->action_set);
  if (set == nullptr || set->instance != found->instance)
    return misuse(XR_ERROR_HANDLE_INVALID, kSelf, "unknown XrAction");
  if (action->type != XR_ACTION_TYPE_POSE_INPUT) {
    return misuse(XR_ERROR_ACTION_TYPE_MISMATCH, kSelf, "action spaces need an XR_ACTION_TYPE_POSE_INPUT action");
  }
  if (create_info->subactionPath != XR_NULL_PATH) {
    if (pathString(*owner, create_info->subactionPath) == nullptr) {
      return misuse(XR_ERROR_PATH_INVALID, kSelf, "unknown subactionPath");
    }
    const std::optional<Hand> hand = handOfPath(*owner, create_info->subactionPath);
    bool listed = false;
    for (Hand subaction : action->subaction_hands) listed = listed || (hand && subaction == *hand);
    if (!listed) return misuse(XR_ERROR_PATH_UNSUPPORTED, kSelf, "subactionPath is not one of the action's");
  }
  if (!isValidPose(create_info->poseInActionSpace)) {
    return misuse(XR_ERROR_POSE_INVALID, kSelf, "poseInActionSpace's orientation is not a unit quaternion");
  }
  auto created = std::make_unique<Space>();
  created->session = idOf(session);
  created->is_action_space = true;
  created->action = idOf(create_info->action);
  created->subaction_path = create_info->subactionPath;
  created->pose_in_space = fromXr(create_info->poseInActionSpace);
  *space = handleOf<XrSpace>(store(runtime().spaces, std::move(created)));
  return sessionSuccess(*found);
}

XrResult XRAPI_CALL xrDestroySpace(XrSpace space) {
  std::lock_guard lock(runtime().mutex);
  if (runtime().spaces.erase(idOf(space)) == 0)
    return misuse(XR_ERROR_HANDLE_INVALID, "xrDestroySpace", "unknown XrSpace");
  return XR_SUCCESS;
}

XrResult XRAPI_CALL xrLocateSpace(XrSpace space, XrSpace base_space, XrTime time, XrSpaceLocation* location) {
  constexpr const char* kSelf = "xrLocateSpace";
  std::lock_guard lock(runtime().mutex);
  const Space* located = find(runtime().spaces, idOf(space));
  const Space* base = find(runtime().spaces, idOf(base_space));
  if (located == nullptr || base == nullptr) return misuse(XR_ERROR_HANDLE_INVALID, kSelf, "unknown XrSpace");
  if (located->session != base->session) {
    return misuse(XR_ERROR_VALIDATION_FAILURE, kSelf, "space and baseSpace belong to different sessions");
  }
  Session* found = nullptr;
  Instance* owner = nullptr;
  if (const XrResult checked = lookUpSession(kSelf, handleOf<XrSession>(located->session), found, owner);
      XR_FAILED(checked)) {
    return checked;
  }
  if (location == nullptr || location->type != XR_TYPE_SPACE_LOCATION) {
    return misuse(XR_ERROR_VALIDATION_FAILURE, kSelf, "location must have type XR_TYPE_SPACE_LOCATION");
  }
  if (time <= 0) return misuse(XR_ERROR_TIME_INVALID, kSelf, "time must be positive");
  // Velocities are not simulated: their valid flags stay clear.
  for (auto* item = static_cast<XrBaseOutStructure*>(location->next); item != nullptr; item = item->next) {
    if (item->type == XR_TYPE_SPACE_VELOCITY) reinterpret_cast<XrSpaceVelocity*>(item)->velocityFlags = 0;
  }
  const std::optional<Pose> located_pose = locateInLocal(*owner, *located, time);
  const std::optional<Pose> base_pose = locateInLocal(*owner, *base, time);
  if (!located_pose || !base_pose) {
    location->locationFlags = 0;
    location->pose = toXr(Pose{});
  } else {
    location->locationFlags = kTracked;
    location->pose = toXr(compose(inverse(*base_pose), *located_pose));
  }
  return sessionSuccess(*found);
}

XrResult XRAPI_CALL xrLocateViews(XrSession session, const XrViewLocateInfo* locate_info, XrViewState* view_state,
                                  uint32_t capacity, uint32_t* count_output, XrView* views) {
  constexpr const char* kSelf = "xrLocateViews";
  std::lock_guard lock(runtime().mutex);
  Session* found = nullptr;
  Instance* owner = nullptr;
  if (const XrResult checked = lookUpSession(kSelf, session, found, owner); XR_FAILED(checked)) return checked;
  if (locate_info == nullptr || locate_info->type != XR_TYPE_VIEW_LOCATE_INFO) {
    return misuse(XR_ERROR_VALIDATION_FAILURE, kSelf, "viewLocateInfo must have type XR_TYPE_VIEW_LOCATE_INFO");
  }
  if (view_state == nullptr || view_state->type != XR_TYPE_VIEW_STATE) {
    return misuse(XR_ERROR_VALIDATION_FAILURE, kSelf, "viewState must have type XR_TYPE_VIEW_STATE");
  }
  if (locate_info->viewConfigurationType != XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO) {
    return misuse(XR_ERROR_VIEW_CONFIGURATION_TYPE_UNSUPPORTED, kSelf,
                  "only XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO is offered");
  }
  if (locate_info->displayTime <= 0) return misuse(XR_ERROR_TIME_INVALID, kSelf, "displayTime must be positive");
  const Space* base = find(runtime().spaces, idOf(locate_info->space));
  if (base == nullptr || base->session != idOf(session)) {
    return misuse(XR_ERROR_HANDLE_INVALID, kSelf, "unknown XrSpace");
  }
  if (capacity > 0 && views == nullptr) return misuse(XR_ERROR_VALIDATION_FAILURE, kSelf, "null views");
  const std::optional<Pose> base_pose = locateInLocal(*owner, *base, locate_info->displayTime);
  const std::uint64_t frame = frameAtTime(owner->script, locate_info->displayTime);
  const XrResult result = fillArray(kSelf, capacity, count_output, 2, [&](std::uint32_t i) {
    if (views[i].type != XR_TYPE_VIEW)
      return misuse(XR_ERROR_VALIDATION_FAILURE, kSelf, "views[] must have type XR_TYPE_VIEW");
    views[i].pose = toXr(base_pose ? compose(inverse(*base_pose), eyePose(owner->script, frame, i)) : Pose{});
    views[i].fov = toXrFov(owner->script.eyeFov(i));
    return XR_SUCCESS;
  });
  if (XR_FAILED(result)) return result;
  view_state->viewStateFlags = base_pose ? kViewTracked : 0;
  return sessionSuccess(*found);
}

}  // namespace plumb::xr_headset
