// Space and view poses (space_poses.h). OpenXR 1.0 specification, chapter 7 "Spaces" (reference
// spaces VIEW, LOCAL, STAGE; action spaces) and chapter 10, section "View and Projection State"
// (xrLocateViews: each view's pose and field of view).

#include "tests/support/xr_headset/space_poses.h"

namespace plumb::xr_headset {

Pose headPose(const HeadsetScript& script, std::uint64_t frame) {
  return script.entryAt(frame).head;
}

Pose eyePose(const HeadsetScript& script, std::uint64_t frame, std::uint32_t eye) {
  const double half_ipd = script.ipd_m / 2;
  Pose offset;
  offset.position.x = eye == 0 ? -half_ipd : half_ipd;
  return compose(headPose(script, frame), offset);
}

std::optional<Pose> locateInLocal(const Instance& instance, const Space& space, XrTime time) {
  const std::uint64_t frame = frameAtTime(instance.script, time);
  if (!space.is_action_space) {
    const Pose base = space.reference_type == XR_REFERENCE_SPACE_TYPE_VIEW ? headPose(instance.script, frame) : Pose{};
    return compose(base, space.pose_in_space);
  }
  const Action* action = find(runtime().actions, space.action);
  if (action == nullptr || action->type != XR_ACTION_TYPE_POSE_INPUT) return std::nullopt;
  // The space's hand: its subaction path's, or the first hand with an active binding.
  std::optional<Hand> hand;
  if (space.subaction_path != XR_NULL_PATH) {
    hand = handOfPath(instance, space.subaction_path);
  } else {
    for (Hand candidate : {Hand::kLeft, Hand::kRight}) {
      if (action->sampled[static_cast<std::size_t>(candidate)].active) {
        hand = candidate;
        break;
      }
    }
  }
  if (!hand) return std::nullopt;
  const SampledInput& sampled = action->sampled[static_cast<std::size_t>(*hand)];
  const HandState& state = instance.script.entryAt(frame).hands[static_cast<std::size_t>(*hand)];
  if (!sampled.active || !state.active) return std::nullopt;
  return compose(sampled.grip_pose ? state.grip : state.aim, space.pose_in_space);
}

}  // namespace plumb::xr_headset
