#pragma once
// Where the head, the eyes and the application's spaces are at a given time, in the LOCAL/STAGE
// space (the script's, which the simulated headset uses for both). OpenXR 1.0 specification,
// chapter 7 "Spaces": VIEW follows the head, an action space follows its action's bound pose.

#include <cstdint>
#include <optional>

#include "tests/support/xr_headset/runtime_state.h"

namespace plumb::xr_headset {

Pose headPose(const HeadsetScript& script, std::uint64_t frame);

// Eye 0 (left) sits ipd/2 to the head's left, eye 1 to its right, oriented as the head.
Pose eyePose(const HeadsetScript& script, std::uint64_t frame, std::uint32_t eye);

// The pose of `space` in LOCAL at `time`; nullopt while it is not tracked: an action space whose
// action has no active pose binding for its hand since the last xrSyncActions.
std::optional<Pose> locateInLocal(const Instance& instance, const Space& space, XrTime time);

}  // namespace plumb::xr_headset
