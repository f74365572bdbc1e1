// Navigation from input events: clicks told from drags, orbit, pan, zoom towards the cursor,
// double-click focus, the standard views and the orthographic toggle.

#include "ui/viewer/navigation.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <gtest/gtest.h>

#include <cmath>

#include "engine/view/camera_controls.h"

namespace plumb::viewer {
namespace {

using Kind = InputEvent::Kind;

const Eigen::Vector3d kMin(512000.0, 5403000.0, 250.0);
const Eigen::Vector3d kMax(512010.0, 5403008.0, 253.0);

InputEvent move(double x, double y) {
  return {.kind = Kind::kMouseMove, .x = x, .y = y};
}
InputEvent button(double x, double y, bool pressed, int which = GLFW_MOUSE_BUTTON_LEFT) {
  return {.kind = Kind::kMouseButton, .x = x, .y = y, .button = which, .pressed = pressed};
}
InputEvent key(int code, bool pressed = true) {
  return {.kind = Kind::kKey, .key = code, .pressed = pressed};
}

// Nothing under the cursor: navigation falls back to the camera's target.
const PickAt kNothing = [](double, double) { return std::optional<Eigen::Vector3d>{}; };

TEST(Navigator, OpensOnAnIsoViewOfTheBounds) {
  const Navigator navigator(kMin, kMax, 640, 360);
  const view::Camera& camera = navigator.camera();
  EXPECT_FALSE(view::findCameraProblem(camera));
  EXPECT_EQ(camera.viewport_width_px, 640);
  // Both corners of the box are in view.
  for (const Eigen::Vector3d& corner : {kMin, kMax}) {
    const auto pixel = view::pixelOf(camera, corner);
    ASSERT_TRUE(pixel);
    EXPECT_GE(pixel->x(), 0.0);
    EXPECT_LE(pixel->x(), 640.0);
    EXPECT_GE(pixel->y(), 0.0);
    EXPECT_LE(pixel->y(), 360.0);
  }
  // An iso view: from above, looking down at the box's centre along a diagonal.
  const Eigen::Vector3d centre = 0.5 * (kMin + kMax);
  EXPECT_LT((camera.target - centre).norm(), 1e-6 * (kMax - kMin).norm());
  const Eigen::Vector3d view = (camera.target - camera.position).normalized();
  EXPECT_LT(view.z(), -0.3) << "looking down";
  EXPECT_GT(std::abs(view.x()), 0.3);
  EXPECT_GT(std::abs(view.y()), 0.3);
}

// An elevation looks straight at its plane from the side the view is on, the vertical up; a
// level plane keeps the view's turn.
TEST(Navigator, AnElevationLooksStraightAtThePlaneFromTheViewsSide) {
  Navigator navigator(kMin, kMax, 640, 360);
  const Eigen::Vector3d wall_point(3.0, 0.0, 1.2);
  const bool in_front = (navigator.camera().position - wall_point).y() < 0.0;
  navigator.showElevation(wall_point, Eigen::Vector3d(0.0, 1.0, 0.0), 4.0);
  const view::Camera& camera = navigator.camera();
  EXPECT_EQ(camera.projection, view::Projection::kOrthographic);
  EXPECT_DOUBLE_EQ(camera.ortho_height_m, 4.0);
  EXPECT_LT((camera.target - wall_point).norm(), 1e-12);
  EXPECT_LT((view::viewDirection(camera) - Eigen::Vector3d(0.0, in_front ? 1.0 : -1.0, 0.0)).norm(), 1e-9);
  EXPECT_LT((camera.up - Eigen::Vector3d::UnitZ()).norm(), 1e-9);
  EXPECT_FALSE(view::findCameraProblem(camera));

  navigator.showElevation({2.0, 2.0, 0.0}, Eigen::Vector3d::UnitZ(), 6.0);  // the floor: its plan
  EXPECT_LT((view::viewDirection(navigator.camera()) - Eigen::Vector3d(0.0, 0.0, -1.0)).norm(), 1e-9);
  EXPECT_FALSE(view::findCameraProblem(navigator.camera()));
}

TEST(Navigator, APressAndReleaseInPlaceIsAClickForTheTool) {
  Navigator navigator(kMin, kMax, 640, 360);
  const view::Camera before = navigator.camera();
  EXPECT_FALSE(navigator.handle(button(100, 100, true), kNothing));
  EXPECT_FALSE(navigator.handle(move(102, 101), kNothing));  // within the slop
  EXPECT_TRUE(navigator.handle(button(102, 101, false), kNothing));
  EXPECT_EQ((navigator.camera().position - before.position).norm(), 0.0);
}

TEST(Navigator, ALeftDragOrbitsAroundThePickedPointWhichKeepsItsPixel) {
  Navigator navigator(kMin, kMax, 640, 360);
  const Eigen::Vector3d pivot = 0.5 * (kMin + kMax) + Eigen::Vector3d(1.0, -0.5, 0.2);
  const auto pixel_before = view::pixelOf(navigator.camera(), pivot);
  ASSERT_TRUE(pixel_before);
  const PickAt picks_pivot = [&](double, double) { return std::optional<Eigen::Vector3d>(pivot); };
  const Eigen::Vector3d eye_before = navigator.camera().position;
  navigator.handle(button(300, 200, true), picks_pivot);
  for (int i = 1; i <= 10; ++i) navigator.handle(move(300 + 8 * i, 200 + 3 * i), picks_pivot);
  EXPECT_FALSE(navigator.handle(button(380, 230, false), picks_pivot)) << "a drag is not a click";
  EXPECT_GT((navigator.camera().position - eye_before).norm(), 0.1);
  const auto pixel_after = view::pixelOf(navigator.camera(), pivot);
  ASSERT_TRUE(pixel_after);
  EXPECT_NEAR((*pixel_after - *pixel_before).norm(), 0.0, 1e-6);
  // The distance to the pivot is kept.
  EXPECT_NEAR((navigator.camera().position - pivot).norm(), (eye_before - pivot).norm(), 1e-6);
}

TEST(Navigator, ARightDragPansWithTheCursor) {
  Navigator navigator(kMin, kMax, 640, 360);
  const Eigen::Vector3d target = navigator.camera().target;
  const auto pixel_before = view::pixelOf(navigator.camera(), target);
  navigator.handle(button(300, 200, true, GLFW_MOUSE_BUTTON_RIGHT), kNothing);
  navigator.handle(move(310, 200), kNothing);
  navigator.handle(move(340, 220), kNothing);
  navigator.handle(button(340, 220, false, GLFW_MOUSE_BUTTON_RIGHT), kNothing);
  const auto pixel_after = view::pixelOf(navigator.camera(), target);
  ASSERT_TRUE(pixel_before && pixel_after);
  // Once past the click slop (4 pixels), the scene follows the cursor all the way.
  EXPECT_NEAR(pixel_after->x() - pixel_before->x(), 40.0, 0.5);
  EXPECT_NEAR(pixel_after->y() - pixel_before->y(), 20.0, 0.5);
}

// Events come in window pixels; the view renders at a scale that dynamic resolution changes while
// it moves. The same drag must turn the view as far at any scale, and a pan must keep what lies
// under the cursor under it: 100 window pixels are 50 of a half-scale render.
TEST(Navigator, ADragMovesTheViewAsFarWhateverTheRenderScale) {
  Navigator full(kMin, kMax, 640, 360), half(kMin, kMax, 320, 180);
  half.setViewport(320, 180, 640);
  for (Navigator* navigator : {&full, &half}) {
    navigator->handle(button(300, 200, true), kNothing);
    for (int i = 1; i <= 10; ++i) navigator->handle(move(300 + 10 * i, 200), kNothing);
    navigator->handle(button(400, 200, false), kNothing);
  }
  EXPECT_NEAR((full.camera().position - half.camera().position).norm(), 0.0, 1e-9);

  const Eigen::Vector3d target = half.camera().target;
  const auto pixel_before = view::pixelOf(half.camera(), target);
  half.handle(button(300, 200, true, GLFW_MOUSE_BUTTON_RIGHT), kNothing);
  half.handle(move(310, 200), kNothing);
  half.handle(move(400, 200), kNothing);
  half.handle(button(400, 200, false, GLFW_MOUSE_BUTTON_RIGHT), kNothing);
  const auto pixel_after = view::pixelOf(half.camera(), target);
  ASSERT_TRUE(pixel_before && pixel_after);
  EXPECT_NEAR(pixel_after->x() - pixel_before->x(), 50.0, 0.5) << "render pixels: (400 - 300) / 2";
}

TEST(Navigator, TheWheelZoomsTowardsThePointUnderTheCursor) {
  Navigator navigator(kMin, kMax, 640, 360);
  const Eigen::Vector3d point = 0.5 * (kMin + kMax) + Eigen::Vector3d(2.0, 1.0, -0.5);
  const PickAt picks_point = [&](double, double) { return std::optional<Eigen::Vector3d>(point); };
  const auto pixel_before = view::pixelOf(navigator.camera(), point);
  const double distance_before = (navigator.camera().position - point).norm();
  navigator.handle({.kind = Kind::kWheel, .x = 200, .y = 150, .wheel_y = 2.0}, picks_point);
  const double distance_after = (navigator.camera().position - point).norm();
  EXPECT_NEAR(distance_after / distance_before, 0.85 * 0.85, 1e-9);
  const auto pixel_after = view::pixelOf(navigator.camera(), point);
  ASSERT_TRUE(pixel_before && pixel_after);
  EXPECT_NEAR((*pixel_after - *pixel_before).norm(), 0.0, 1e-6);
}

TEST(Navigator, ADoubleClickFocusesOnThePoint) {
  Navigator navigator(kMin, kMax, 640, 360);
  const Eigen::Vector3d point = kMin + Eigen::Vector3d(3.0, 2.0, 1.0);
  const PickAt picks_point = [&](double, double) { return std::optional<Eigen::Vector3d>(point); };
  const double distance_before = (navigator.camera().position - point).norm();
  EXPECT_FALSE(navigator.handle(button(320, 180, true), picks_point)) << "a press is no click yet";
  EXPECT_TRUE(navigator.handle(button(320, 180, false), picks_point));  // the first click goes to the tool
  navigator.update(0.1);
  navigator.handle(button(320, 180, true), picks_point);
  EXPECT_FALSE(navigator.handle(button(320, 180, false), picks_point)) << "the second click focuses instead";
  EXPECT_NEAR((navigator.camera().target - point).norm(), 0.0, 1e-9);
  EXPECT_NEAR((navigator.camera().position - point).norm(), 0.5 * distance_before, 1e-6);
}

TEST(Navigator, TwoQuickClicksAtDifferentPlacesAreTwoClicks) {
  Navigator navigator(kMin, kMax, 640, 360);
  navigator.handle(button(320, 180, true), kNothing);
  EXPECT_TRUE(navigator.handle(button(320, 180, false), kNothing));
  navigator.update(0.1);
  navigator.handle(button(400, 220, true), kNothing);
  EXPECT_TRUE(navigator.handle(button(400, 220, false), kNothing)) << "a measurement's second end, not a focus";
}

TEST(Navigator, TwoSlowClicksAreTwoClicks) {
  Navigator navigator(kMin, kMax, 640, 360);
  navigator.handle(button(320, 180, true), kNothing);
  EXPECT_TRUE(navigator.handle(button(320, 180, false), kNothing));
  navigator.update(1.0);
  navigator.handle(button(320, 180, true), kNothing);
  EXPECT_TRUE(navigator.handle(button(320, 180, false), kNothing));
}

// A grow at the screen's centre, a new view centred on the next seed, a grow there: two quick
// clicks at one pixel, but on two views, so two clicks for the tool (the second grow was lost to a
// focus when the machine was fast enough to make them quick).
TEST(Navigator, QuickClicksAtOnePixelOnTwoViewsAreTwoClicks) {
  Navigator navigator(kMin, kMax, 640, 360);
  navigator.handle(button(320, 180, true), kNothing);
  EXPECT_TRUE(navigator.handle(button(320, 180, false), kNothing));
  navigator.update(0.1);
  navigator.showPreset(view::ViewPreset::kTop);
  navigator.handle(button(320, 180, true), kNothing);
  EXPECT_TRUE(navigator.handle(button(320, 180, false), kNothing)) << "a click on the new view, not a focus";
}

TEST(Navigator, KeysShowTheStandardViewsAndHome) {
  Navigator navigator(kMin, kMax, 640, 360);
  const view::Camera home = navigator.camera();
  navigator.handle(key(GLFW_KEY_1), kNothing);
  EXPECT_EQ(navigator.camera().projection, view::Projection::kOrthographic);
  EXPECT_NEAR(view::viewDirection(navigator.camera()).z(), -1.0, 1e-9) << "top looks down";
  navigator.handle(key(GLFW_KEY_2), kNothing);
  EXPECT_NEAR(view::viewDirection(navigator.camera()).y(), 1.0, 1e-9) << "front looks along +y";
  navigator.handle(key(GLFW_KEY_H), kNothing);
  EXPECT_NEAR((navigator.camera().position - home.position).norm(), 0.0, 1e-9);
}

TEST(Navigator, TheOrthographicToggleKeepsTheExtentAtTheTarget) {
  Navigator navigator(kMin, kMax, 640, 360);
  const view::Camera perspective = navigator.camera();
  const double distance = (perspective.target - perspective.position).norm();
  navigator.toggleOrthographic();
  const view::Camera& ortho = navigator.camera();
  ASSERT_EQ(ortho.projection, view::Projection::kOrthographic);
  EXPECT_NEAR(ortho.ortho_height_m, 2.0 * distance * std::tan(perspective.fov_deg * M_PI / 360.0), 1e-9);
  navigator.toggleOrthographic();
  EXPECT_EQ(navigator.camera().projection, view::Projection::kPerspective);
  EXPECT_NEAR((navigator.camera().position - perspective.position).norm(), 0.0, 1e-6);
}

TEST(Navigator, FlyModeMovesWithHeldKeys) {
  Navigator navigator(kMin, kMax, 640, 360);
  navigator.handle(key(GLFW_KEY_F), kNothing);
  ASSERT_TRUE(navigator.flying());
  const view::Camera before = navigator.camera();
  navigator.handle(key(GLFW_KEY_W), kNothing);
  navigator.update(0.5);
  navigator.handle(key(GLFW_KEY_W, false), kNothing);
  navigator.update(0.5);  // released: no more motion
  const Eigen::Vector3d moved = navigator.camera().position - before.position;
  EXPECT_GT(moved.norm(), 0.1);
  EXPECT_NEAR(moved.normalized().dot(view::viewDirection(before)), 1.0, 1e-9) << "W flies forwards";
  // The fly speed is a tenth of the box's diagonal per second (at least half a metre).
  EXPECT_NEAR(moved.norm(), 0.5 * 0.1 * (kMax - kMin).norm(), 1e-6);
}

}  // namespace
}  // namespace plumb::viewer
