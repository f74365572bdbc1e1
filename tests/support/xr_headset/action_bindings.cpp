// Binding paths to the script's controller state (action_bindings.h). The click threshold for
// values read as booleans is 0.5: a half-pulled trigger clicks.

#include "tests/support/xr_headset/action_bindings.h"

#include <string>

namespace plumb::xr_headset {
namespace {

constexpr float kClickThreshold = 0.5f;

struct NamedSource {
  std::string_view component;  // after "/user/hand/<side>/"
  InputSource source;
};

constexpr NamedSource kSources[] = {
    {"input/trigger/value", InputSource::kTriggerValue},
    {"input/trigger", InputSource::kTriggerValue},
    {"input/trigger/click", InputSource::kTriggerClick},
    {"input/select/click", InputSource::kTriggerClick},
    {"input/select", InputSource::kTriggerClick},
    {"input/squeeze/value", InputSource::kSqueezeValue},
    {"input/squeeze", InputSource::kSqueezeValue},
    {"input/squeeze/click", InputSource::kSqueezeClick},
    {"input/thumbstick", InputSource::kThumbstick},
    {"input/thumbstick/x", InputSource::kThumbstickX},
    {"input/thumbstick/y", InputSource::kThumbstickY},
    {"input/thumbstick/click", InputSource::kThumbstickClick},
    {"input/a/click", InputSource::kButtonA},
    {"input/a", InputSource::kButtonA},
    {"input/b/click", InputSource::kButtonB},
    {"input/b", InputSource::kButtonB},
    {"input/x/click", InputSource::kButtonX},
    {"input/x", InputSource::kButtonX},
    {"input/y/click", InputSource::kButtonY},
    {"input/y", InputSource::kButtonY},
    {"input/menu/click", InputSource::kButtonMenu},
    {"input/menu", InputSource::kButtonMenu},
    {"input/aim/pose", InputSource::kAimPose},
    {"input/aim", InputSource::kAimPose},
    {"input/grip/pose", InputSource::kGripPose},
    {"input/grip", InputSource::kGripPose},
};

std::optional<bool> buttonOf(const HandState& hand, InputSource source) {
  switch (source) {
    case InputSource::kTriggerValue:
    case InputSource::kTriggerClick:
      return hand.trigger > kClickThreshold;
    case InputSource::kSqueezeValue:
    case InputSource::kSqueezeClick:
      return hand.squeeze > kClickThreshold;
    case InputSource::kThumbstickClick:
      return hand.thumbstick_click;
    case InputSource::kButtonA:
      return hand.a;
    case InputSource::kButtonB:
      return hand.b;
    case InputSource::kButtonX:
      return hand.x;
    case InputSource::kButtonY:
      return hand.y;
    case InputSource::kButtonMenu:
      return hand.menu;
    default:
      return std::nullopt;
  }
}

std::optional<float> valueOf(const HandState& hand, InputSource source) {
  switch (source) {
    case InputSource::kTriggerValue:
      return hand.trigger;
    case InputSource::kSqueezeValue:
      return hand.squeeze;
    case InputSource::kThumbstickX:
      return hand.thumbstick_x;
    case InputSource::kThumbstickY:
      return hand.thumbstick_y;
    default: {
      // Clicks read as 0 or 1.
      const std::optional<bool> button = buttonOf(hand, source);
      if (!button) return std::nullopt;
      return *button ? 1.0f : 0.0f;
    }
  }
}

}  // namespace

std::optional<BoundInput> parseBindingPath(std::string_view path) {
  BoundInput bound;
  constexpr std::string_view kLeft = "/user/hand/left/", kRight = "/user/hand/right/";
  std::string_view component;
  if (path.starts_with(kLeft)) {
    bound.hand = Hand::kLeft;
    component = path.substr(kLeft.size());
  } else if (path.starts_with(kRight)) {
    bound.hand = Hand::kRight;
    component = path.substr(kRight.size());
  } else {
    return std::nullopt;
  }
  for (const NamedSource& named : kSources) {
    if (named.component == component) {
      bound.source = named.source;
      return bound;
    }
  }
  return std::nullopt;
}

std::optional<InputReading> readInput(const HandState& hand, InputSource source, XrActionType type) {
  InputReading reading;
  switch (type) {
    case XR_ACTION_TYPE_BOOLEAN_INPUT: {
      const std::optional<bool> button = buttonOf(hand, source);
      if (!button) return std::nullopt;
      reading.boolean = *button;
      return reading;
    }
    case XR_ACTION_TYPE_FLOAT_INPUT: {
      const std::optional<float> value = valueOf(hand, source);
      if (!value) return std::nullopt;
      reading.value = *value;
      return reading;
    }
    case XR_ACTION_TYPE_VECTOR2F_INPUT:
      if (source != InputSource::kThumbstick) return std::nullopt;
      reading.vector = {hand.thumbstick_x, hand.thumbstick_y};
      return reading;
    case XR_ACTION_TYPE_POSE_INPUT:
      if (source != InputSource::kAimPose && source != InputSource::kGripPose) return std::nullopt;
      reading.grip_pose = source == InputSource::kGripPose;
      return reading;
    default:
      return std::nullopt;  // outputs read nothing
  }
}

}  // namespace plumb::xr_headset
