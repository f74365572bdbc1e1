#include "ui/xr/stage.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "ui/xr/hand_panel.h"

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

// The model in one hand: the world point the hand held stays in the hand as it moves and
// turns; world distances do not change.
TEST(Stage, AHeldWorldFollowsTheHand) {
  StagePlacement start;
  start.origin = {10.0, 20.0, 0.0};
  start.heading_rad = 0.3;
  start.scale = 20.0;
  const Pose from = standing(0.1, 1.1, -0.4, 0.0);
  const Pose to = standing(-0.2, 1.3, -0.5, 0.5);  // moved and turned 0.5 rad to the left
  const StagePlacement moved = dragged(start, holdOf(from), holdOf(to));
  EXPECT_TRUE(moved.toWorld(to.position).isApprox(start.toWorld(from.position), kTight));
  EXPECT_NEAR(moved.scale, 20.0, kTight);
  // A point 10 cm in front of the hand stays 10 cm in front of it, in the hand's own turn.
  const Eigen::Vector3d ahead_from = from.position + from.orientation * Eigen::Vector3d(0.0, 0.0, -0.1);
  const Eigen::Vector3d ahead_to = to.position + to.orientation * Eigen::Vector3d(0.0, 0.0, -0.1);
  EXPECT_TRUE(moved.toWorld(ahead_to).isApprox(start.toWorld(ahead_from), 1e-9));
}

// Two hands: pulling them apart to twice their distance doubles the model's size (halves the
// world metres a stage metre holds), about the point between them.
TEST(Stage, TwoHandsApartEnlargeTheModelAboutTheirMiddle) {
  StagePlacement start;
  start.scale = 50.0;
  const Pose left_from = standing(-0.1, 1.2, -0.4), right_from = standing(0.1, 1.2, -0.4);
  const Pose left_to = standing(-0.2, 1.2, -0.4), right_to = standing(0.2, 1.2, -0.4);
  const StagePlacement moved = dragged(start, holdOf(left_from, right_from), holdOf(left_to, right_to));
  EXPECT_NEAR(moved.scale, 25.0, kTight);
  const Eigen::Vector3d middle(0.0, 1.2, -0.4);
  EXPECT_TRUE(moved.toWorld(middle).isApprox(start.toWorld(middle), kTight));
  // Each hand holds the world point it held, as the model grows under them.
  const Eigen::Vector3d held = start.toWorld(right_from.position);
  EXPECT_TRUE(moved.toStage(held).isApprox(right_to.position, kTight));
}

TEST(Stage, WalkingAndTurningMoveTheWorldUnderTheUser) {
  StagePlacement start;
  start.origin = {100.0, 100.0, 0.0};
  const Eigen::Vector3d head(0.3, 1.6, 0.2);
  // One metre forward: the head's world position moves one metre along the stage's forward.
  const StagePlacement walked_one = walked(start, {0.0, 0.0, -1.0});
  EXPECT_TRUE((walked_one.toWorld(head) - start.toWorld(head)).isApprox(Eigen::Vector3d::UnitY(), kTight));
  // A quarter turn to the left about the head: the head stays, forward becomes world -x.
  const StagePlacement quarter = turned(start, head, std::numbers::pi / 2.0);
  EXPECT_TRUE(quarter.toWorld(head).isApprox(start.toWorld(head), kTight));
  EXPECT_TRUE(quarter.directionToWorld({0.0, 0.0, -1.0}).isApprox(-Eigen::Vector3d::UnitX(), kTight));
}

TEST(Stage, AModelOnTheTableFitsItsSizeAtItsPlace) {
  const StagePlacement start;
  const Eigen::Vector3d low(512000.0, 5403000.0, 250.0), high(512030.0, 5403012.0, 259.0);
  const Eigen::Vector3d table(0.0, 1.0, -0.5);
  const StagePlacement model = modelOnTable(start, low, high, table, 0.6);
  EXPECT_NEAR(model.scale, 50.0, kTight);
  EXPECT_TRUE(model.toStage(0.5 * (low + high)).isApprox(table, 1e-9));
  EXPECT_NEAR((model.toStage(high) - model.toStage(low)).norm(), (high - low).norm() / 50.0, 1e-9);
}

// Both eyes' nodes come from one view: every point either eye sees lies in it, at the eyes'
// pixel density.
TEST(Stage, TheBothEyesViewHoldsWhatEachEyeSees) {
  StagePlacement placement;
  placement.origin = {10.0, 10.0, 0.0};
  const view::EyeFov left_fov{-0.87, 0.70, 0.73, -0.80}, right_fov{-0.70, 0.87, 0.73, -0.80};
  const view::Camera left = eyeCamera(placement, standing(-0.032, 1.6, 0.0), left_fov, 600, 500);
  const view::Camera right = eyeCamera(placement, standing(0.032, 1.6, 0.0), right_fov, 600, 500);
  const view::Camera both = bothEyesCamera(left, right);
  ASSERT_FALSE(view::findCameraProblem(both));
  const auto inside = [](const view::Camera& camera, const Eigen::Vector3d& world) {
    const Eigen::Vector4d clip = view::projectionMatrix(camera) * view::viewMatrix(camera) * world.homogeneous();
    return clip.w() > 0.0 && std::abs(clip.x()) <= clip.w() * (1 + 1e-9) && std::abs(clip.y()) <= clip.w() * (1 + 1e-9);
  };
  // The corners of each eye's image at 10 cm and at 20 m.
  for (const view::Camera* eye : {&left, &right}) {
    const Eigen::Matrix4d to_world = (view::projectionMatrix(*eye) * view::viewMatrix(*eye)).inverse();
    for (const double depth_ndc : {-0.99, 0.999}) {
      for (const double x : {-1.0, 1.0}) {
        for (const double y : {-1.0, 1.0}) {
          const Eigen::Vector4d world = to_world * Eigen::Vector4d(x, y, depth_ndc, 1.0);
          EXPECT_TRUE(inside(both, world.head<3>() / world.w())) << x << " " << y << " " << depth_ndc;
        }
      }
    }
  }
  EXPECT_NEAR(view::metresPerPixel(both, 3.0), view::metresPerPixel(left, 3.0), 1e-4);
}

// The panel in the left hand: a ray at its centre meets it at (0.5, 0.5); its top left corner
// is near (0, 0); a ray from behind or beside it misses.
TEST(HandPanel, ARayMeetsThePanelWhereItPoints) {
  const Pose hand = standing(-0.2, 1.1, -0.35);
  const HandPanel panel = panelOnHand(hand, 16.0 / 9.0);
  EXPECT_NEAR(panel.height_m, 0.36 * 9.0 / 16.0, kTight);
  const Eigen::Vector3d normal = panel.pose.orientation * Eigen::Vector3d::UnitZ();
  EXPECT_GT(normal.dot(Eigen::Vector3d(0.0, 1.6, 0.0) - panel.pose.position), 0.0) << "it faces the eyes";

  const auto aimAt = [](const Eigen::Vector3d& from, const Eigen::Vector3d& to) {
    Pose aim;
    aim.position = from;
    aim.orientation = Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d(0.0, 0.0, -1.0), (to - from).normalized());
    return aim;
  };
  const Eigen::Vector3d right_hand(0.25, 1.2, -0.1);
  const std::optional<Eigen::Vector2d> centre = panelPoint(panel, aimAt(right_hand, panel.pose.position));
  ASSERT_TRUE(centre);
  EXPECT_TRUE(centre->isApprox(Eigen::Vector2d(0.5, 0.5), 1e-9));
  const Eigen::Vector3d top_left =
      panel.pose.position + panel.pose.orientation * Eigen::Vector3d(-0.49 * panel.width_m, 0.49 * panel.height_m, 0);
  const std::optional<Eigen::Vector2d> corner = panelPoint(panel, aimAt(right_hand, top_left));
  ASSERT_TRUE(corner);
  EXPECT_NEAR(corner->x(), 0.01, 1e-9);
  EXPECT_NEAR(corner->y(), 0.01, 1e-9);
  // From behind the panel, and past its edge.
  EXPECT_FALSE(panelPoint(panel, aimAt(panel.pose.position - 0.3 * normal, panel.pose.position)));
  const Eigen::Vector3d beside = panel.pose.position + panel.pose.orientation * Eigen::Vector3d(0.3, 0.0, 0.0);
  EXPECT_FALSE(panelPoint(panel, aimAt(right_hand, beside)));
}

}  // namespace
}  // namespace plumb::xr
