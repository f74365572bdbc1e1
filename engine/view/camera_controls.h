#pragma once
// Camera navigation: the maths of orbit, pan, zoom-to-point and fly, on cameras in world
// coordinates (double precision). ui/ maps mouse and keys to these; they know nothing of input.
// Each takes a valid camera and returns a valid one (viewport, projection and clip distances
// unchanged except where said). Screen deltas are in pixels, x right and y down, as the mouse.

#include <Eigen/Core>
#include <optional>

#include "engine/view/camera.h"

namespace plumb::view {

// The pixel (x right, y down, from the top-left corner; pixel centres at .5) where `world`
// appears; nothing when it lies behind the eye (perspective).
std::optional<Eigen::Vector2d> pixelOf(const Camera& camera, const Eigen::Vector3d& world);

struct Ray {
  Eigen::Vector3d origin;
  Eigen::Vector3d direction;  // unit
};

// The ray from the eye through the pixel position (x, y) (perspective: from the eye; orthographic:
// from the eye's plane, parallel to the view direction).
Ray rayThroughPixel(const Camera& camera, double x_px, double y_px);

// The parameter s of the point of the line p + s d (d unit) nearest to `ray`; nothing when they
// are parallel. What a drag along a line follows (an edge's snap, a box face's handle).
std::optional<double> lineParameterNearestRay(const Eigen::Vector3d& p, const Eigen::Vector3d& d, const Ray& ray);

// Where `ray` meets the plane through `point` with `normal` (any length), in front of its origin;
// nothing when it runs parallel to it or the plane lies behind.
std::optional<Eigen::Vector3d> rayHitOnPlane(const Ray& ray, const Eigen::Vector3d& point,
                                             const Eigen::Vector3d& normal);

// Turns the eye around `pivot` (usually the picked point or the target): by `yaw` about the
// world's z axis and by `pitch` about the camera's right axis, positive pitch looking down more.
// The pivot keeps its pixel; the pitch stops a degree short of looking straight up or down.
Camera orbit(const Camera& camera, const Eigen::Vector3d& pivot, double yaw_rad, double pitch_rad);

// Moves eye and target in the view plane so that what lies at the target's depth follows the
// cursor by (dx, dy) pixels.
Camera pan(const Camera& camera, double dx_px, double dy_px);

// Moves towards `point` (perspective: the eye, by factor of its distance; orthographic: the
// view height is scaled by factor) so that `point` keeps its pixel. factor < 1 zooms in.
Camera zoomToPoint(const Camera& camera, const Eigen::Vector3d& point, double factor);

// First-person flight: moves eye and target by `move` metres along the camera's right, up and
// forward axes, then looks around the eye by `yaw` (about world z) and `pitch`.
Camera fly(const Camera& camera, const Eigen::Vector3d& move_right_up_forward, double yaw_rad, double pitch_rad);

}  // namespace plumb::view
