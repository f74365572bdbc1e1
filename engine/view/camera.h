#pragma once
// A camera in world coordinates (double precision) and the OpenGL-style matrices it implies.
//
// Conventions, the same as reco::ViewAtClick (reco/parameters.h), which the matrices feed:
// - viewMatrix maps world to camera space; the camera sits at the origin of camera space and looks
//   down its -z axis, +y is the screen's up, +x its right (right-handed).
// - projectionMatrix maps camera to clip space as glFrustum / glOrtho do: after the divide by w, x
//   and y run from -1 to 1 over the viewport (y up) and depth from -1 at the near plane to +1 at
//   the far plane. A Vulkan renderer (depth 0..1, y down) converts with its own correction matrix.
//
// Plain data: copy freely, no thread-safety concerns.

#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <string>

namespace plumb::view {

enum class Projection : std::uint8_t { kPerspective, kOrthographic };

// An off-axis perspective frustum, a headset's eye (OpenXR's XrFovf): the angles of its four
// sides from the view direction, radians, left and down negative for a frustum that holds the
// view direction. Each side within (-pi/2, pi/2), left < right, down < up.
struct EyeFov {
  double left = -0.8, right = 0.8, up = 0.8, down = -0.8;
};

struct Camera {
  Eigen::Vector3d position{0.0, -10.0, 0.0};  // the eye, world coordinates
  Eigen::Vector3d target{0.0, 0.0, 0.0};      // the look-at point, world coordinates
  Eigen::Vector3d up{0.0, 0.0, 1.0};          // any length, not parallel to target - position
  Projection projection = Projection::kPerspective;
  double fov_deg = 60.0;  // vertical field of view (perspective), [kMinFovDeg, 180)
  // Perspective only: replaces fov_deg and the viewport's aspect ratio with an off-axis frustum
  // (a headset's eye; its pixels need not be square then).
  std::optional<EyeFov> eye_fov;
  double ortho_height_m = 10.0;   // the world height the viewport shows (orthographic)
  int viewport_width_px = 1920;   // > 0
  int viewport_height_px = 1080;  // > 0
  double near_m = 0.05;           // clip distances along the view direction, kMinExtent <= near < far
  double far_m = 10'000.0;
};

// What is wrong with a camera: the field (named as in the JSON file, docs/camera-json.md) and why.
struct CameraProblem {
  std::string field;
  std::string what;
};

// The first rule `camera` breaks, or nothing when it is valid. The rules: every number finite;
// position and target coordinates within kMaxCoordinate and at least kMinTargetDistance apart;
// up not zero and at least kMinUpAngle radians away from the view direction; fov_deg in
// [kMinFovDeg, 180); eye_fov, when set, as EyeFov says; ortho_height_m at least kMinExtent; viewport sizes > 0;
// kMinExtent <= near_m < far_m <= kMaxFar. Every field is checked whatever the projection. The limits keep every entry
// of viewMatrix and projectionMatrix finite.
std::optional<CameraProblem> findCameraProblem(const Camera& camera);

// Throws plumb::Error "camera: field '<field>': <what>" when findCameraProblem finds a problem.
void validateCamera(const Camera& camera);

constexpr double kMinTargetDistance = 1e-6;  // metres
constexpr double kMinUpAngle = 1e-6;         // radians between up and the view direction
// Beyond these, the matrices overflow: 1 / tan of a tiny angle, 2 / a tiny view height or depth
// range, 2 far near / (near - far), a translation of huge coordinates. Far wider than any scan.
constexpr double kMaxCoordinate = 1e12;  // metres, of position and target
constexpr double kMinFovDeg = 1e-6;      // degrees
constexpr double kMinExtent = 1e-6;      // metres, of ortho_height_m and near_m
constexpr double kMaxFar = 1e12;         // metres

// The unit view direction, (target - position) normalised. The camera must be valid.
Eigen::Vector3d viewDirection(const Camera& camera);

// World -> camera (rigid: rotation and translation). The camera must be valid (assert).
// The translation carries the full world coordinates: apply it in double precision.
Eigen::Matrix4d viewMatrix(const Camera& camera);

// Camera -> clip, OpenGL style (see the top of this file). Perspective (gluPerspective, or
// glFrustum for an eye_fov): the projection(3, 3) entry is 0 and the w row is (0, 0, -1, 0); orthographic: the last row
// is (0, 0, 0, 1), the viewport showing ortho_height_m by ortho_height_m * aspect. The camera must be valid (assert).
Eigen::Matrix4d projectionMatrix(const Camera& camera);

// viewport_width_px / viewport_height_px.
double aspectRatio(const Camera& camera);

// Metres per pixel in the plane at `depth` in front of the eye (orthographic: at any depth),
// vertically.
double metresPerPixel(const Camera& camera, double depth);

}  // namespace plumb::view
