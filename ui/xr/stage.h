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

// A controller's aim ray in the world: its origin and unit direction (the pose's -z).
struct WorldRay {
  Eigen::Vector3d origin;
  Eigen::Vector3d direction;
};
WorldRay aimRay(const StagePlacement& placement, const Pose& aim);

}  // namespace plumb::xr
