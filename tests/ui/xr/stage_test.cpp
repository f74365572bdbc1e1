#include "ui/xr/stage.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace plumb::xr {
namespace {

constexpr double kTight = 1e-9;

Pose standing(double x, double y, double z, double yaw_rad = 0.0) {
  Pose pose;
  pose.position = {x, y, z};
  pose.orientation = Eigen::AngleAxisd(yaw_rad, Eigen::Vector3d::UnitY());  // OpenXR's up is +y
  return pose;
}

// The stage's axes (OpenXR: y up, -z forward) become the world's (z up, +y forward) at heading 0.
TEST(Stage, OpenXrsAxesTurnToTheWorldsZUp) {
  const StagePlacement placement;
  EXPECT_TRUE(placement.directionToWorld({0.0, 1.0, 0.0}).isApprox(Eigen::Vector3d::UnitZ(), kTight));
  EXPECT_TRUE(placement.directionToWorld({0.0, 0.0, -1.0}).isApprox(Eigen::Vector3d::UnitY(), kTight));
  EXPECT_TRUE(placement.directionToWorld({1.0, 0.0, 0.0}).isApprox(Eigen::Vector3d::UnitX(), kTight));
}

TEST(Stage, WorldAndStageAreInverse) {
  StagePlacement placement;
  placement.origin = {512000.0, 5403000.0, 250.0};
  placement.heading_rad = 0.7;
  placement.scale = 40.0;
  const Eigen::Vector3d stage(0.3, 1.2, -0.8);
  EXPECT_TRUE(placement.toStage(placement.toWorld(stage)).isApprox(stage, kTight));
  // Scale: a stage metre is 40 world metres.
  EXPECT_NEAR((placement.toWorld({1.0, 0.0, 0.0}) - placement.toWorld({0.0, 0.0, 0.0})).norm(), 40.0, 1e-6);
}

// Placed at a desktop camera, the head stands where the camera is and faces where it faces,
// level, whatever the head's own yaw in the stage.
TEST(Stage, APlacementPutsTheHeadWhereTheCameraIs) {
  view::Camera camera;
  camera.position = {10.0, 20.0, 1.7};
  camera.target = {7.0, 24.0, 0.5};  // looking down a little, towards -x +y
  const Pose head = standing(0.4, 1.6, -0.2, 0.9);
  const StagePlacement placement = placementAt(camera, head);
  EXPECT_TRUE(placement.toWorld(head.position).isApprox(camera.position, kTight));
  const Eigen::Vector3d forward = placement.directionToWorld(head.orientation * Eigen::Vector3d(0.0, 0.0, -1.0));
  const Eigen::Vector3d level_view = Eigen::Vector3d(-3.0, 4.0, 0.0).normalized();
  EXPECT_TRUE(forward.isApprox(level_view, kTight));
}

// An eye's camera: at the eye, looking along its -z, up its +y, with the eye's frustum; at
// scale s its near plane is s times further, so a model in the hands clips as a building does.
TEST(Stage, AnEyesCameraFollowsTheEyesPose) {
  StagePlacement placement;
  placement.origin = {100.0, 200.0, 10.0};
  placement.heading_rad = std::numbers::pi / 2.0;  // stage forward -> world -x
  placement.scale = 2.0;
  const Pose eye = standing(-0.032, 1.6, 0.0);
  const view::EyeFov fov{-0.9, 0.7, 0.8, -0.8};
  const view::Camera camera = eyeCamera(placement, eye, fov, 640, 480);
  EXPECT_FALSE(view::findCameraProblem(camera));
  EXPECT_TRUE(camera.position.isApprox(Eigen::Vector3d(100.0, 200.0 - 0.064, 13.2), kTight));
  EXPECT_TRUE(view::viewDirection(camera).isApprox(-Eigen::Vector3d::UnitX(), kTight));
  EXPECT_TRUE(camera.up.normalized().isApprox(Eigen::Vector3d::UnitZ(), kTight));
  ASSERT_TRUE(camera.eye_fov);
  EXPECT_EQ(camera.eye_fov->left, -0.9);
  EXPECT_NEAR(camera.near_m, 0.1, kTight);
  EXPECT_EQ(camera.viewport_width_px, 640);
}

TEST(Stage, AControllersAimRayPointsAlongItsMinusZ) {
  const StagePlacement placement;
  Pose aim = standing(0.2, 1.0, -0.3);
  aim.orientation = Eigen::AngleAxisd(-std::numbers::pi / 4.0, Eigen::Vector3d::UnitX());  // pitched down 45 deg
  const WorldRay ray = aimRay(placement, aim);
  EXPECT_TRUE(ray.origin.isApprox(Eigen::Vector3d(0.2, 0.3, 1.0), kTight));
  EXPECT_TRUE(ray.direction.isApprox(Eigen::Vector3d(0.0, 1.0, -1.0).normalized(), kTight));
}

}  // namespace
}  // namespace plumb::xr
