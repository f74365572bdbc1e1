#pragma once
// How a suggested binding's path reads the script's controller state (OpenXR 1.0 specification,
// chapter 6, section "Interaction Profile Paths": /user/hand/<left|right>/input/<identifier>/<component>;
// chapter 11, section "Suggested Bindings": a float bound to a boolean action reads as a click past
// a threshold, a click bound to a float action reads 0 or 1). Component-less paths
// (".../input/trigger") read the identifier's natural value, as the specification allows.

#include <optional>
#include <string_view>

#include "tests/support/xr_headset/headset_script.h"
#include "tests/support/xr_headset/xr_api.h"

namespace plumb::xr_headset {

enum class InputSource {
  kTriggerValue,
  kTriggerClick,  // also .../input/select/click
  kSqueezeValue,
  kSqueezeClick,
  kThumbstick,
  kThumbstickX,
  kThumbstickY,
  kThumbstickClick,
  kButtonA,
  kButtonB,
  kButtonX,
  kButtonY,
  kButtonMenu,
  kAimPose,
  kGripPose,
};

struct BoundInput {
  Hand hand = Hand::kLeft;
  InputSource source = InputSource::kTriggerValue;
};

// The hand and input `path` reads; nullopt for anything the script does not simulate (outputs,
// other top-level paths, unknown identifiers).
std::optional<BoundInput> parseBindingPath(std::string_view path);

struct InputReading {
  bool boolean = false;
  float value = 0;
  XrVector2f vector{};
  bool grip_pose = false;  // pose actions: the grip pose, else the aim pose
};

// What `source` of `hand` gives an action of `type`; nullopt when it cannot feed that type.
std::optional<InputReading> readInput(const HandState& hand, InputSource source, XrActionType type);

}  // namespace plumb::xr_headset
