#include "reco/parameters.h"

#include <gtest/gtest.h>

#include <cmath>

namespace plumb::reco {
namespace {

Eigen::Matrix4d perspective(double fovy_deg, double aspect, double near, double far) {
  const double f = 1.0 / std::tan(fovy_deg * M_PI / 360.0);
  Eigen::Matrix4d p = Eigen::Matrix4d::Zero();
  p(0, 0) = f / aspect;
  p(1, 1) = f;
  p(2, 2) = (far + near) / (near - far);
  p(2, 3) = 2.0 * far * near / (near - far);
  p(3, 2) = -1.0;
  return p;
}

Eigen::Matrix4d orthographic(double half_height, double aspect) {
  Eigen::Matrix4d p = Eigen::Matrix4d::Identity();
  p(0, 0) = 1.0 / (half_height * aspect);
  p(1, 1) = 1.0 / half_height;
  p(2, 2) = -0.01;
  return p;
}

// A camera at UTM coordinates looking along -z (the view matrix moves the eye to the origin).
ViewAtClick lookingDown(const Eigen::Vector3d& eye, double distance, const Eigen::Matrix4d& projection) {
  ViewAtClick view;
  view.view.setIdentity();
  view.view.block<3, 1>(0, 3) = -eye;
  view.projection = projection;
  view.picked = eye - Eigen::Vector3d(0, 0, distance);
  return view;
}

TEST(Parameters, SeedRadiusIsATenthOfTheScreenWidthAtThePickedDepth) {
  const Eigen::Vector3d eye(512000.0, 5403000.0, 260.0);
  const ViewAtClick view = lookingDown(eye, 3.0, perspective(60.0, 1920.0 / 1080.0, 0.1, 1000.0));
  const GrowParameters p = parametersForView(view);
  const double screen_height = 2.0 * 3.0 * std::tan(M_PI / 6.0);
  const double screen_width = screen_height * 1920.0 / 1080.0;
  EXPECT_NEAR(p.pixel_size_m, screen_height / 1080.0, 1e-12);
  EXPECT_NEAR(p.seed_radius_m, 0.1 * screen_width, 1e-9);
  EXPECT_EQ(p.seed, view.picked);
  EXPECT_NEAR(p.spacing_m, std::cbrt(1.0 / p.density), 1e-12);
  EXPECT_NEAR(p.search_radius_m, 2.0 * p.spacing_m, 1e-12);
  EXPECT_EQ(p.plane_threshold_m, ParameterConstants{}.plane_threshold_m);
}

TEST(Parameters, DensityFallsLogarithmicallyWithDistanceBetweenItsLimits) {
  const Eigen::Vector3d eye(0, 0, 0);
  const Eigen::Matrix4d projection = perspective(60.0, 16.0 / 9.0, 0.01, 1000.0);
  double previous = INFINITY;
  for (double distance : {0.1, 0.5, 1.0, 3.0, 10.0, 30.0, 100.0, 300.0}) {
    const double density = parametersForView(lookingDown(eye, distance, projection)).density;
    EXPECT_LE(density, previous) << distance;
    EXPECT_GE(density, 100.0);
    EXPECT_LE(density, 10'000.0);
    previous = density;
  }
  EXPECT_EQ(parametersForView(lookingDown(eye, 0.1, projection)).density, 10'000.0);
  EXPECT_NEAR(parametersForView(lookingDown(eye, 300.0, projection)).density, 100.0, 1e-9);
  // Logarithmic: equal ratios of pixel size give equal ratios of density in between.
  const double d3 = parametersForView(lookingDown(eye, 3.0, projection)).density;
  const double d6 = parametersForView(lookingDown(eye, 6.0, projection)).density;
  const double d12 = parametersForView(lookingDown(eye, 12.0, projection)).density;
  EXPECT_NEAR(d3 / d6, d6 / d12, 1e-9);
}

TEST(Parameters, DetailFollowsTheDataDownToEveryPointWherePixelsAreAsFineAsThePoints) {
  const ParameterConstants c;
  const DataAtClick scan{.spacing_m = 0.005, .full_density = 1e10};
  EXPECT_EQ(densityForPixel(0.0049, c, scan), scan.full_density);
  EXPECT_EQ(densityForPixel(0.005, c, scan), scan.full_density);
  // Just coarser than the points: the data's own density, then the logarithmic fall to the
  // paper's far end.
  EXPECT_NEAR(densityForPixel(0.005001, c, scan) / std::pow(0.005, -3.0), 1.0, 0.01);
  EXPECT_NEAR(densityForPixel(0.02, c, scan), c.min_density, 1e-9);
  EXPECT_NEAR(densityForPixel(0.5, c, scan), c.min_density, 1e-9);
  const double d1 = densityForPixel(0.006, c, scan), d2 = densityForPixel(0.009, c, scan),
               d3 = densityForPixel(0.0135, c, scan);
  EXPECT_NEAR(d1 / d2, d2 / d3, 1e-9 * d1 / d2);
  EXPECT_GT(d2, d3);
  // Points finer than the near pixel: every point from half a metre (pixels of 0.5 mm) on.
  const DataAtClick dense{.spacing_m = 0.0002, .full_density = 1e12};
  EXPECT_EQ(densityForPixel(c.near_pixel_m, c, dense), dense.full_density);
  EXPECT_LT(densityForPixel(1.1 * c.near_pixel_m, c, dense), dense.full_density);
  // Points farther apart than the far pixel: every point up to their spacing, then one octave
  // of fall.
  const DataAtClick sparse{.spacing_m = 0.05, .full_density = 1e7};
  EXPECT_EQ(densityForPixel(0.05, c, sparse), sparse.full_density);
  EXPECT_GT(densityForPixel(0.07, c, sparse), c.min_density);
  EXPECT_NEAR(densityForPixel(0.1, c, sparse), c.min_density, 1e-9);
  // No data measured (an isolated point): the paper's mapping.
  EXPECT_EQ(densityForPixel(0.003, c, DataAtClick{}), densityForPixel(0.003, c, std::nullopt));
}

TEST(Parameters, FollowingTheDataNeverAsksForFewerPointsThanThePapersMapping) {
  const ParameterConstants c;
  for (double spacing : {0.0001, 0.0005, 0.001, 0.005, 0.02, 0.046, 0.1, 0.3}) {
    const DataAtClick data{.spacing_m = spacing, .full_density = 1e13};
    for (double pixel = 1e-4; pixel < 1.0; pixel *= 1.1) {
      EXPECT_GE(densityForPixel(pixel, c, data), densityForPixel(pixel, c, std::nullopt) * (1.0 - 1e-12))
          << "spacing " << spacing << ", pixel " << pixel;
    }
  }
}

TEST(Parameters, AClickThatFollowsTheDataKeepsItsSpacing) {
  const ViewAtClick view = viewFromDistance({1, 2, 3}, 0.4);  // pixels of 0.43 mm
  const GrowParameters p = parametersForView(view, {}, DataAtClick{.spacing_m = 0.004, .full_density = 1e9});
  EXPECT_EQ(p.click_spacing_m, 0.004);
  EXPECT_EQ(p.density, 1e9);
  EXPECT_EQ(parametersForView(view).click_spacing_m, 0.0);
  EXPECT_EQ(parametersForView(view).density, ParameterConstants{}.max_density);
}

TEST(Parameters, OrthographicPixelsDoNotDependOnDepth) {
  const Eigen::Matrix4d projection = orthographic(5.0, 16.0 / 9.0);
  const double near = parametersForView(lookingDown({0, 0, 0}, 2.0, projection)).pixel_size_m;
  const double far = parametersForView(lookingDown({0, 0, 0}, 50.0, projection)).pixel_size_m;
  EXPECT_EQ(near, far);
  ViewAtClick view = lookingDown({0, 0, 0}, 2.0, projection);
  EXPECT_NEAR(pixelSizeAt(view), 10.0 / view.viewport_height_px, 1e-12);
}

}  // namespace
}  // namespace plumb::reco
