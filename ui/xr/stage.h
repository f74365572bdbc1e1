#pragma once
// Where the headset's tracked space (its stage) lies in the cloud's world, and the cameras and
// rays that follow from it. The one seam between OpenXR's axes (+y up, -z forward) and Plumb's
// world (+z up, double precision): every pose from the headset passes through here.
//
// Plain data and math: copy freely, no thread-safety concerns.

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "engine/view/camera.h"

namespace plumb::xr {

// A pose in the stage, metres, OpenXR's axes.
struct Pose {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();
};

// world = origin + scale * Rz(heading) * A * stage, where A turns OpenXR's axes to the world's
// (x stays, y up becomes z, -z forward becomes +y).
struct StagePlacement {
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();  // the world point of the stage's origin
  double heading_rad = 0.0;                          // about the world's z: 0 maps the stage's forward to world +y
  // World metres per stage metre: 1 walks the building at full size; above 1 the building is a
  // model held in the hands (at 50 a 20 m floor spans 40 cm).
  double scale = 1.0;

  Eigen::Vector3d toWorld(const Eigen::Vector3d& stage_point) const;
  Eigen::Vector3d directionToWorld(const Eigen::Vector3d& stage_direction) const;  // unit length
  Eigen::Vector3d toStage(const Eigen::Vector3d& world_point) const;
};

// The placement, at `scale`, that puts a head standing at `head` where `camera` is, facing
// where it faces (horizontally: the head stays level).
StagePlacement placementAt(const view::Camera& camera, const Pose& head, double scale = 1.0);

// The camera of an eye at `eye` with the frustum `fov`, rendering width x height pixels. Its
// near plane is `near_stage_m` in the stage (a hand's breadth), scaled with the placement.
view::Camera eyeCamera(const StagePlacement& placement, const Pose& eye, const view::EyeFov& fov, int width, int height,
                       double near_stage_m = 0.05);

// What a hand or two hold of the world while they move it (the model in the hands): a point in
// the stage (the grabbing hand, or the middle between two), a yaw about the stage's up (the
// hand's heading, or the line between the hands') and a span (1, or the hands' distance).
struct Hold {
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  double yaw_rad = 0.0;
  double span = 1.0;
};

// One hand's hold (its position and heading), and two hands' (their middle, the heading of the
// line between them, their distance).
Hold holdOf(const Pose& hand);
Hold holdOf(const Pose& left, const Pose& right);

// The placement that keeps the world under the hold as it moves `from` -> `to`: the world point
// held at from.point is at to.point afterwards, turned by the yaw's change about the vertical,
// scaled by from.span / to.span about it (pulling the hands apart enlarges the model).
StagePlacement dragged(const StagePlacement& start, const Hold& from, const Hold& to);

// The user walks `stage_offset` (metres in the stage, horizontal for a level walk): the world
// slides the other way under them, scaled with the placement.
StagePlacement walked(const StagePlacement& placement, const Eigen::Vector3d& stage_offset);

// The user turns by `angle_rad` (positive: to the left, counter-clockwise seen from above)
// about the vertical through `pivot` in the stage (the head).
StagePlacement turned(const StagePlacement& placement, const Eigen::Vector3d& pivot, double angle_rad);

// The model on a table: the world box `bounds_min`..`bounds_max` scaled to span `size_m` at most
// and centred at `centre` in the stage, keeping the placement's heading.
StagePlacement modelOnTable(const StagePlacement& placement, const Eigen::Vector3d& bounds_min,
                            const Eigen::Vector3d& bounds_max, const Eigen::Vector3d& centre, double size_m = 0.6);

// A view that holds what both eyes see, for choosing the nodes both draw: from between the
// eyes, moved back until the two frusta fit in the union of their sides; the eyes' pixel density.
view::Camera bothEyesCamera(const view::Camera& left, const view::Camera& right);

// A controller's aim ray in the world: its origin and unit direction (the pose's -z).
struct WorldRay {
  Eigen::Vector3d origin;
  Eigen::Vector3d direction;
};
WorldRay aimRay(const StagePlacement& placement, const Pose& aim);

}  // namespace plumb::xr
