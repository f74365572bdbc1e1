// Quaternion and pose arithmetic for the simulated headset (OpenXR 1.0 specification, section 2.16
// "Coordinate System": XrQuaternionf is (x, y, z, w), XrPosef rotates then translates).

#include "tests/support/xr_headset/pose_math.h"

#include <cmath>

namespace plumb::xr_headset {
namespace {

Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
double length(const Vec3& v) {
  return std::sqrt(v.x * v.x + v.y * v.y + v.z * v.z);
}
Vec3 scaled(const Vec3& v, double s) {
  return {v.x * s, v.y * s, v.z * s};
}

// The rotation whose matrix has columns x_axis, y_axis, z_axis (orthonormal, right-handed).
Quat fromAxes(const Vec3& x_axis, const Vec3& y_axis, const Vec3& z_axis) {
  const double trace = x_axis.x + y_axis.y + z_axis.z;
  Quat q;
  // Branch on the largest diagonal term: the square root stays away from zero.
  if (trace > 0) {
    const double s = 2 * std::sqrt(1 + trace);
    q = {(y_axis.z - z_axis.y) / s, (z_axis.x - x_axis.z) / s, (x_axis.y - y_axis.x) / s, s / 4};
  } else if (x_axis.x > y_axis.y && x_axis.x > z_axis.z) {
    const double s = 2 * std::sqrt(1 + x_axis.x - y_axis.y - z_axis.z);
    q = {s / 4, (y_axis.x + x_axis.y) / s, (z_axis.x + x_axis.z) / s, (y_axis.z - z_axis.y) / s};
  } else if (y_axis.y > z_axis.z) {
    const double s = 2 * std::sqrt(1 + y_axis.y - x_axis.x - z_axis.z);
    q = {(y_axis.x + x_axis.y) / s, s / 4, (z_axis.y + y_axis.z) / s, (z_axis.x - x_axis.z) / s};
  } else {
    const double s = 2 * std::sqrt(1 + z_axis.z - x_axis.x - y_axis.y);
    q = {(z_axis.x + x_axis.z) / s, (z_axis.y + y_axis.z) / s, s / 4, (x_axis.y - y_axis.x) / s};
  }
  return q;
}

}  // namespace

Vec3 rotate(const Quat& q, const Vec3& v) {
  // v' = v + 2w (u x v) + 2 u x (u x v), u the vector part.
  const Vec3 u{q.x, q.y, q.z};
  const Vec3 t = scaled(cross(u, v), 2);
  const Vec3 u_t = cross(u, t);
  return {v.x + q.w * t.x + u_t.x, v.y + q.w * t.y + u_t.y, v.z + q.w * t.z + u_t.z};
}

Quat multiply(const Quat& a, const Quat& b) {
  return {a.w * b.x + a.x * b.w + a.y * b.z - a.z * b.y, a.w * b.y - a.x * b.z + a.y * b.w + a.z * b.x,
          a.w * b.z + a.x * b.y - a.y * b.x + a.z * b.w, a.w * b.w - a.x * b.x - a.y * b.y - a.z * b.z};
}

Pose compose(const Pose& parent, const Pose& child) {
  const Vec3 offset = rotate(parent.orientation, child.position);
  return {{parent.position.x + offset.x, parent.position.y + offset.y, parent.position.z + offset.z},
          multiply(parent.orientation, child.orientation)};
}

Pose inverse(const Pose& pose) {
  const Quat conjugate{-pose.orientation.x, -pose.orientation.y, -pose.orientation.z, pose.orientation.w};
  const Vec3 back = rotate(conjugate, pose.position);
  return {{-back.x, -back.y, -back.z}, conjugate};
}

std::optional<Quat> lookAt(const Vec3& eye, const Vec3& target) {
  const Vec3 forward{target.x - eye.x, target.y - eye.y, target.z - eye.z};
  const double forward_length = length(forward);
  if (forward_length < 1e-9) return std::nullopt;
  const Vec3 z_axis = scaled(forward, -1 / forward_length);  // OpenXR looks down -z
  const Vec3 x_unnormalised = cross(Vec3{0, 1, 0}, z_axis);
  const double x_length = length(x_unnormalised);
  if (x_length < 1e-9) return std::nullopt;
  const Vec3 x_axis = scaled(x_unnormalised, 1 / x_length);
  return fromAxes(x_axis, cross(z_axis, x_axis), z_axis);
}

Pose fromXr(const XrPosef& pose) {
  return {{pose.position.x, pose.position.y, pose.position.z},
          {pose.orientation.x, pose.orientation.y, pose.orientation.z, pose.orientation.w}};
}

XrPosef toXr(const Pose& pose) {
  XrPosef out{};
  out.orientation = {static_cast<float>(pose.orientation.x), static_cast<float>(pose.orientation.y),
                     static_cast<float>(pose.orientation.z), static_cast<float>(pose.orientation.w)};
  out.position = {static_cast<float>(pose.position.x), static_cast<float>(pose.position.y),
                  static_cast<float>(pose.position.z)};
  return out;
}

}  // namespace plumb::xr_headset
