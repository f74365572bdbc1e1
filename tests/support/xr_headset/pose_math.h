#pragma once
// Rigid poses of the simulated headset, in OpenXR's convention (OpenXR 1.0 specification,
// section 2.16 "Coordinate System" and chapter 7 "Spaces"): right-handed, +y up, -z forward,
// orientations as unit quaternions (x, y, z, w). Doubles inside, XrPosef at the API.

#include <optional>

#include "tests/support/xr_headset/xr_api.h"

namespace plumb::xr_headset {

struct Vec3 {
  double x = 0, y = 0, z = 0;
};

struct Quat {
  double x = 0, y = 0, z = 0, w = 1;
};

// A frame placed in a parent frame: a point p of the frame is at orientation * p + position in the parent.
struct Pose {
  Vec3 position;
  Quat orientation;
};

Vec3 rotate(const Quat& q, const Vec3& v);
Quat multiply(const Quat& a, const Quat& b);

// `child`, given in `parent`'s frame, expressed in the frame `parent` is given in.
Pose compose(const Pose& parent, const Pose& child);
Pose inverse(const Pose& pose);

// The orientation that looks from `eye` at `target` with +y up (its -z axis towards the target);
// nullopt when the target is at the eye or straight above or below it.
std::optional<Quat> lookAt(const Vec3& eye, const Vec3& target);

Pose fromXr(const XrPosef& pose);
XrPosef toXr(const Pose& pose);

}  // namespace plumb::xr_headset
