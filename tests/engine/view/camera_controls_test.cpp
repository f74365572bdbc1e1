// Orbit, pan, zoom-to-point and fly: what stays where on screen.

#include "engine/view/camera_controls.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace plumb::view {
namespace {

constexpr double kPixelTolerance = 1e-6;

Camera perspective() {
  Camera camera;
  camera.position = {512010.0, 5403002.0, 253.5};  // UTM-sized coordinates: precision matters
  camera.target = {512005.0, 5403006.0, 251.0};
  camera.viewport_width_px = 1600;
  camera.viewport_height_px = 900;
  return camera;
}

Camera orthographic() {
  Camera camera = perspective();
  camera.projection = Projection::kOrthographic;
  camera.ortho_height_m = 8.0;
  return camera;
}

void expectSamePixel(const Camera& before, const Camera& after, const Eigen::Vector3d& point) {
  const auto a = pixelOf(before, point), b = pixelOf(after, point);
  ASSERT_TRUE(a && b);
  EXPECT_NEAR(a->x(), b->x(), kPixelTolerance);
  EXPECT_NEAR(a->y(), b->y(), kPixelTolerance);
}

TEST(CameraControls, TheTargetIsAtTheCentreAndRaysHitWhatTheyShow) {
  for (const Camera& camera : {perspective(), orthographic()}) {
    const auto centre = pixelOf(camera, camera.target);
    ASSERT_TRUE(centre);
    EXPECT_NEAR(centre->x(), 800.0, kPixelTolerance);
    EXPECT_NEAR(centre->y(), 450.0, kPixelTolerance);
    // A point along the ray through a pixel appears at that pixel.
    const Ray ray = rayThroughPixel(camera, 123.25, 777.5);
    const auto pixel = pixelOf(camera, ray.origin + 7.0 * ray.direction);
    ASSERT_TRUE(pixel);
    EXPECT_NEAR(pixel->x(), 123.25, kPixelTolerance);
    EXPECT_NEAR(pixel->y(), 777.5, kPixelTolerance);
  }
  EXPECT_FALSE(pixelOf(perspective(), perspective().position - viewDirection(perspective())));  // behind
}

TEST(CameraControls, OrbitKeepsThePivotsPixelAndDistance) {
  const Eigen::Vector3d pivot(512006.0, 5403005.0, 250.5);
  for (const Camera& camera : {perspective(), orthographic()}) {
    const Camera turned = orbit(camera, pivot, 0.7, -0.3);
    expectSamePixel(camera, turned, pivot);
    EXPECT_NEAR((turned.position - pivot).norm(), (camera.position - pivot).norm(), 1e-9);
    EXPECT_FALSE(findCameraProblem(turned));
  }
  // A full turn of yaw comes back.
  const Camera camera = perspective();
  Camera around = camera;
  for (int step = 0; step < 8; ++step) around = orbit(around, pivot, std::numbers::pi / 4, 0.0);
  EXPECT_LT((around.position - camera.position).norm(), 1e-8);
  EXPECT_LT((around.target - camera.target).norm(), 1e-8);
}

TEST(CameraControls, OrbitStopsShortOfThePoles) {
  const Camera camera = perspective();
  const Camera down = orbit(camera, camera.target, 0.0, 10.0);  // far past straight down
  const double elevation = std::asin(viewDirection(down).z());
  EXPECT_NEAR(elevation, -std::numbers::pi / 2 + std::numbers::pi / 180.0, 1e-9);
  EXPECT_FALSE(findCameraProblem(down));
  const Camera up = orbit(camera, camera.target, 0.0, -10.0);
  EXPECT_NEAR(std::asin(viewDirection(up).z()), std::numbers::pi / 2 - std::numbers::pi / 180.0, 1e-9);
  // Pitch looks down for positive angles.
  EXPECT_LT(viewDirection(orbit(camera, camera.target, 0.0, 0.1)).z(), viewDirection(camera).z());
}

TEST(CameraControls, PanMovesWhatLiesAtTheTargetDepthWithTheCursor) {
  for (const Camera& camera : {perspective(), orthographic()}) {
    const Camera moved = pan(camera, 40.0, -25.0);
    const auto before = pixelOf(camera, camera.target), after = pixelOf(moved, camera.target);
    ASSERT_TRUE(before && after);
    EXPECT_NEAR(after->x() - before->x(), 40.0, 1e-6);
    EXPECT_NEAR(after->y() - before->y(), -25.0, 1e-6);
    EXPECT_LT((viewDirection(moved) - viewDirection(camera)).norm(), 1e-12);
  }
}

TEST(CameraControls, ZoomToPointKeepsThePointUnderTheCursor) {
  const Eigen::Vector3d point(512006.5, 5403004.0, 252.0);  // off the centre
  for (const Camera& camera : {perspective(), orthographic()}) {
    const Camera in = zoomToPoint(camera, point, 0.5);
    expectSamePixel(camera, in, point);
    if (camera.projection == Projection::kPerspective) {
      EXPECT_NEAR((in.position - point).norm(), 0.5 * (camera.position - point).norm(), 1e-9);
    } else {
      EXPECT_NEAR(in.ortho_height_m, 4.0, 1e-12);
    }
    expectSamePixel(in, zoomToPoint(in, point, 3.0), point);
  }
}

TEST(CameraControls, FlyMovesAlongTheCameraAxesAndLooksAroundTheEye) {
  const Camera camera = perspective();
  const Camera forward = fly(camera, {0.0, 0.0, 2.0}, 0.0, 0.0);
  EXPECT_LT((forward.position - (camera.position + 2.0 * viewDirection(camera))).norm(), 1e-9);
  EXPECT_LT((viewDirection(forward) - viewDirection(camera)).norm(), 1e-12);
  const Camera looked = fly(camera, Eigen::Vector3d::Zero(), 0.4, 0.2);
  EXPECT_EQ(looked.position, camera.position);
  // The yaw turns about world z: the horizontal heading changes by it.
  const auto heading = [](const Camera& c) { return std::atan2(viewDirection(c).y(), viewDirection(c).x()); };
  EXPECT_NEAR(heading(looked) - heading(camera), 0.4, 1e-9);
  EXPECT_GT((viewDirection(looked) - viewDirection(camera)).norm(), 0.1);
  EXPECT_FALSE(findCameraProblem(looked));
}

}  // namespace
}  // namespace plumb::view
