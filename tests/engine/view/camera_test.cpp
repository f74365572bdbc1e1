#include "engine/view/camera.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <limits>
#include <numbers>

#include "engine/core/error.h"
#include "reco/parameters.h"

namespace plumb::view {
namespace {

constexpr double kTight = 1e-9;  // matrix arithmetic on numbers of order 1

// The camera of the pixel-size check: 3 m from `target` along -y, looking along +y, z up.
//
//        z
//        |   position          target
//        +----o---------3 m------x------> y
Camera cameraThreeMetresFrom(const Eigen::Vector3d& target) {
  Camera camera;
  camera.target = target;
  camera.position = target - Eigen::Vector3d(0.0, 3.0, 0.0);
  camera.up = Eigen::Vector3d(0.0, 0.0, 1.0);
  camera.fov_deg = 60.0;
  camera.viewport_width_px = 1920;
  camera.viewport_height_px = 1080;
  return camera;
}

reco::ViewAtClick viewAtClick(const Camera& camera, const Eigen::Vector3d& picked) {
  reco::ViewAtClick view;
  view.view = viewMatrix(camera);
  view.projection = projectionMatrix(camera);
  view.viewport_width_px = camera.viewport_width_px;
  view.viewport_height_px = camera.viewport_height_px;
  view.picked = picked;
  return view;
}

// Normalised device coordinates of a world point.
Eigen::Vector3d ndc(const Camera& camera, const Eigen::Vector3d& world) {
  const Eigen::Vector4d camera_space = viewMatrix(camera) * world.homogeneous();
  const Eigen::Vector4d clip = projectionMatrix(camera) * camera_space;
  return clip.head<3>() / clip.w();
}

TEST(Camera, DefaultIsValid) {
  EXPECT_FALSE(findCameraProblem(Camera{}).has_value());
}

TEST(Camera, ViewMatrixIsRigidAndLooksDownMinusZ) {
  const Camera camera = cameraThreeMetresFrom({1.0, 2.0, 3.0});
  const Eigen::Matrix4d view = viewMatrix(camera);
  const Eigen::Matrix3d rotation = view.block<3, 3>(0, 0);
  EXPECT_TRUE((rotation * rotation.transpose()).isApprox(Eigen::Matrix3d::Identity(), kTight));
  EXPECT_NEAR(rotation.determinant(), 1.0, kTight);
  // The target lies 3 m ahead, on -z; the position at the origin; world up is screen up.
  const Eigen::Vector4d target = view * camera.target.homogeneous();
  EXPECT_NEAR(target.x(), 0.0, kTight);
  EXPECT_NEAR(target.y(), 0.0, kTight);
  EXPECT_NEAR(target.z(), -3.0, kTight);
  EXPECT_TRUE((view * camera.position.homogeneous()).head<3>().isZero(kTight));
  EXPECT_TRUE((rotation * Eigen::Vector3d::UnitZ()).isApprox(Eigen::Vector3d::UnitY(), kTight));
  // Looking along +y with z up, +x is to the right.
  EXPECT_TRUE((rotation * Eigen::Vector3d::UnitX()).isApprox(Eigen::Vector3d::UnitX(), kTight));
}

TEST(Camera, PerspectiveProjectsTheTargetToTheViewportCentre) {
  const Camera camera = cameraThreeMetresFrom({512000.0, 5403000.0, 250.0});
  const Eigen::Vector3d centre = ndc(camera, camera.target);
  EXPECT_NEAR(centre.x(), 0.0, 1e-9);
  EXPECT_NEAR(centre.y(), 0.0, 1e-9);
  EXPECT_GT(centre.z(), -1.0);
  EXPECT_LT(centre.z(), 1.0);
  // The top edge of the view at 3 m: 3 tan(30 deg) above the target.
  const Eigen::Vector3d top = ndc(camera, camera.target + Eigen::Vector3d(0, 0, 3.0 * std::tan(std::numbers::pi / 6)));
  EXPECT_NEAR(top.y(), 1.0, 1e-9);
  // The right edge: wider by the aspect ratio.
  const Eigen::Vector3d right =
      ndc(camera, camera.target + Eigen::Vector3d(3.0 * std::tan(std::numbers::pi / 6) * 1920.0 / 1080.0, 0, 0));
  EXPECT_NEAR(right.x(), 1.0, 1e-9);
}

TEST(Camera, DepthRunsFromMinusOneAtNearToOneAtFar) {
  Camera camera = cameraThreeMetresFrom({0.0, 0.0, 0.0});
  camera.near_m = 0.5;
  camera.far_m = 100.0;
  const Eigen::Vector3d forward = viewDirection(camera);
  EXPECT_NEAR(ndc(camera, camera.position + 0.5 * forward).z(), -1.0, 1e-9);
  EXPECT_NEAR(ndc(camera, camera.position + 100.0 * forward).z(), 1.0, 1e-9);
  camera.projection = Projection::kOrthographic;
  EXPECT_NEAR(ndc(camera, camera.position + 0.5 * forward).z(), -1.0, 1e-9);
  EXPECT_NEAR(ndc(camera, camera.position + 100.0 * forward).z(), 1.0, 1e-9);
}

TEST(Camera, PixelSizeAtThreeMetresMatchesTheFieldOfView) {
  const Eigen::Vector3d target(512000.0, 5403000.0, 250.0);
  const Camera camera = cameraThreeMetresFrom(target);
  const double expected = 2.0 * 3.0 * std::tan(std::numbers::pi / 6.0) / 1080.0;
  EXPECT_NEAR(reco::pixelSizeAt(viewAtClick(camera, target)), expected, 1e-12);
  // The same numbers as reco's own 60-degree camera at 3 m.
  EXPECT_NEAR(reco::pixelSizeAt(reco::viewFromDistance(target, 3.0)), expected, 1e-12);
  const reco::GrowParameters parameters = reco::parametersForView(viewAtClick(camera, target));
  EXPECT_NEAR(parameters.pixel_size_m, expected, 1e-12);
  EXPECT_NEAR(parameters.seed_radius_m, 0.1 * expected * 1920.0, 1e-9);
}

TEST(Camera, OrthographicPixelSizeIsTheViewHeightOverThePixels) {
  Camera camera = cameraThreeMetresFrom({0.0, 0.0, 0.0});
  camera.projection = Projection::kOrthographic;
  camera.ortho_height_m = 10.8;
  EXPECT_NEAR(reco::pixelSizeAt(viewAtClick(camera, camera.target)), 0.01, 1e-12);
  const Eigen::Vector3d top = ndc(camera, camera.target + Eigen::Vector3d(0, 0, 5.4));
  EXPECT_NEAR(top.y(), 1.0, 1e-12);
  EXPECT_NEAR(ndc(camera, camera.target).x(), 0.0, 1e-12);
}

// A headset's eye looks through an off-axis frustum: each side of the image lies at its own
// angle from the view direction (OpenXR's XrFovf), here wider towards the nose (+x, the left eye).
//
//      left -40 deg \   | view   / right +50 deg
//                    \  |       /
//                     \ |     /
//                       eye
TEST(Camera, AnEyesFrustumPutsEachSideAtItsOwnAngle) {
  Camera camera = cameraThreeMetresFrom({10.0, 20.0, 30.0});
  camera.viewport_width_px = 900;
  camera.viewport_height_px = 1000;
  const double deg = std::numbers::pi / 180.0;
  camera.eye_fov = EyeFov{-40.0 * deg, 50.0 * deg, 45.0 * deg, -35.0 * deg};
  ASSERT_FALSE(findCameraProblem(camera));
  // Camera space here: +x is world +x, +y is world +z, the view along world +y.
  const auto at = [&](double x_angle, double y_angle) -> Eigen::Vector3d {
    return camera.target + Eigen::Vector3d(3.0 * std::tan(x_angle), 0.0, 3.0 * std::tan(y_angle));
  };
  EXPECT_NEAR(ndc(camera, at(-40.0 * deg, 0.0)).x(), -1.0, kTight);
  EXPECT_NEAR(ndc(camera, at(50.0 * deg, 0.0)).x(), 1.0, kTight);
  EXPECT_NEAR(ndc(camera, at(0.0, 45.0 * deg)).y(), 1.0, kTight);
  EXPECT_NEAR(ndc(camera, at(0.0, -35.0 * deg)).y(), -1.0, kTight);
  // The view direction is off the image's centre, towards its wider side.
  EXPECT_LT(ndc(camera, camera.target).x(), 0.0);
  // Depth is unchanged by the sides.
  Camera symmetric = camera;
  symmetric.eye_fov.reset();
  EXPECT_NEAR(ndc(camera, camera.target).z(), ndc(symmetric, camera.target).z(), kTight);
  // A pixel's height at 3 m: the frustum's height there over the rows, as reco measures it.
  const double expected = 3.0 * (std::tan(45.0 * deg) + std::tan(35.0 * deg)) / 1000.0;
  EXPECT_NEAR(metresPerPixel(camera, 3.0), expected, 1e-12);
  EXPECT_NEAR(reco::pixelSizeAt(viewAtClick(camera, camera.target)), expected, 1e-12);
}

TEST(Camera, AnEyesFrustumMustHoldTogether) {
  Camera camera = cameraThreeMetresFrom({0.0, 0.0, 0.0});
  camera.eye_fov = EyeFov{0.5, -0.5, 0.5, -0.5};
  ASSERT_TRUE(findCameraProblem(camera));
  EXPECT_EQ(findCameraProblem(camera)->field, "eye_fov");
  camera.eye_fov = EyeFov{-0.5, 0.5, 1.6, -0.5};  // beyond 90 degrees
  EXPECT_EQ(findCameraProblem(camera)->field, "eye_fov");
  camera.eye_fov = EyeFov{-0.5, std::numeric_limits<double>::quiet_NaN(), 0.5, -0.5};
  EXPECT_EQ(findCameraProblem(camera)->field, "eye_fov");
  camera.eye_fov = EyeFov{0.1, 0.5, 0.6, 0.2};  // wholly to one side: allowed
  EXPECT_FALSE(findCameraProblem(camera));
}

TEST(Camera, ValidationNamesTheBrokenRule) {
  const auto field = [](const Camera& camera) {
    const auto problem = findCameraProblem(camera);
    return problem ? problem->field : std::string("(valid)");
  };
  const Camera good = cameraThreeMetresFrom({0.0, 0.0, 0.0});
  Camera c = good;
  c.position.x() = std::nan("");
  EXPECT_EQ(field(c), "position");
  c = good;
  c.target.z() = INFINITY;
  EXPECT_EQ(field(c), "target");
  c = good;
  c.target = c.position;
  EXPECT_EQ(field(c), "target");
  c = good;
  c.up = Eigen::Vector3d(0.0, 2.0, 0.0);  // along the view direction
  EXPECT_EQ(field(c), "up");
  c.up = Eigen::Vector3d::Zero();
  EXPECT_EQ(field(c), "up");
  for (const double fov : {0.0, -10.0, 180.0, 200.0}) {
    c = good;
    c.fov_deg = fov;
    EXPECT_EQ(field(c), "fov_deg") << fov;
  }
  c = good;
  c.ortho_height_m = 0.0;
  EXPECT_EQ(field(c), "ortho_height_m");
  c = good;
  c.viewport_height_px = 0;
  EXPECT_EQ(field(c), "viewport");
  c = good;
  c.near_m = 0.0;
  EXPECT_EQ(field(c), "near_m");
  c = good;
  c.far_m = c.near_m;
  EXPECT_EQ(field(c), "far_m");
  EXPECT_THROW(validateCamera(c), Error);
  EXPECT_NO_THROW(validateCamera(good));
}

// Found by the camera fuzz target: cameras whose numbers were finite but whose matrices were not
// (an orthographic view 1e-320 m high made 2 / height infinite). Each limit is the one that keeps
// its matrix entry finite.
TEST(Camera, LimitsKeepTheMatricesFinite) {
  const auto field = [](const Camera& camera) {
    const auto problem = findCameraProblem(camera);
    return problem ? problem->field : std::string("(valid)");
  };
  Camera c;
  c.position.x() = 2e12;
  EXPECT_EQ(field(c), "position");
  c = Camera{};
  c.target.y() = -2e12;
  EXPECT_EQ(field(c), "target");
  c = Camera{};
  c.fov_deg = 1e-320;
  EXPECT_EQ(field(c), "fov_deg");
  c = Camera{};
  c.ortho_height_m = 1e-320;
  EXPECT_EQ(field(c), "ortho_height_m");
  c = Camera{};
  c.near_m = 1e-310;
  c.far_m = 2e-310;
  EXPECT_EQ(field(c), "near_m");
  c = Camera{};
  c.far_m = 1e300;
  EXPECT_EQ(field(c), "far_m");

  // At the limits, in both projections, with the most extreme viewport: finite matrices.
  Camera edge;
  edge.position = Eigen::Vector3d(kMaxCoordinate, -kMaxCoordinate, kMaxCoordinate);
  edge.target = Eigen::Vector3d(-kMaxCoordinate, kMaxCoordinate, -kMaxCoordinate);
  edge.fov_deg = kMinFovDeg;
  edge.ortho_height_m = kMinExtent;
  edge.near_m = kMinExtent;
  edge.far_m = std::nextafter(kMinExtent, 1.0);
  edge.viewport_width_px = 1;
  edge.viewport_height_px = std::numeric_limits<int>::max();
  for (const Projection projection : {Projection::kPerspective, Projection::kOrthographic}) {
    edge.projection = projection;
    ASSERT_EQ(field(edge), "(valid)");
    EXPECT_TRUE(viewMatrix(edge).allFinite());
    EXPECT_TRUE(projectionMatrix(edge).allFinite());
    edge.far_m = kMaxFar;
    EXPECT_TRUE(projectionMatrix(edge).allFinite());
    edge.far_m = std::nextafter(kMinExtent, 1.0);
  }
}

}  // namespace
}  // namespace plumb::view
