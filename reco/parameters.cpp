// Automatic parameters, paper section 3.7.
//
//   1. The picked point's depth in camera space; the size of one pixel there: for a perspective
//      projection 2 * depth / (P11 * height), for an orthographic one 2 / (P11 * height).
//   2. r_s = 10 % of the screen width at that depth (pixel size * viewport width * 0.1).
//   3. d from the pixel size, logarithmic between the near and the far constants; where the
//      data's spacing at the click is known, the near end is the data's own (every point where
//      the pixel is as fine as the points are apart).
//   4. r = 2 mean spacings at density d, the spacing being d^(-1/3).
//   5. t_p is the user's setting, or by default measured by the grower from the seed planes'
//      noise (noise_threshold.h).

#include "reco/parameters.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cassert>
#include <cmath>

namespace plumb::reco {

ViewAtClick viewFromDistance(const Eigen::Vector3d& picked, double distance) {
  ViewAtClick view;
  view.view.setIdentity();
  view.view.block<3, 1>(0, 3) = -(picked + Eigen::Vector3d(0, 0, distance));
  const double f = 1.0 / std::tan(M_PI / 6.0);
  const double near = 0.01, far = 10'000.0;
  view.projection.setZero();
  view.projection(0, 0) = f * view.viewport_height_px / view.viewport_width_px;
  view.projection(1, 1) = f;
  view.projection(2, 2) = (far + near) / (near - far);
  view.projection(2, 3) = 2.0 * far * near / (near - far);
  view.projection(3, 2) = -1.0;
  view.picked = picked;
  return view;
}

double pixelSizeAt(const ViewAtClick& view) {
  const Eigen::Vector4d camera = view.view * view.picked.homogeneous();
  const double p11 = view.projection(1, 1);
  const bool perspective = view.projection(3, 3) == 0.0;  // the w row of a perspective matrix is (0 0 -1 0)
  if (!perspective) return 2.0 / (p11 * view.viewport_height_px);
  const double depth = -camera.z();
  assert(depth > 0.0 && "the picked point must lie in front of the camera");
  return 2.0 * depth / (p11 * view.viewport_height_px);
}

GrowParameters parametersForDensity(const Eigen::Vector3d& seed, double density, double seed_radius_m,
                                    const ParameterConstants& c) {
  GrowParameters p;
  p.seed = seed;
  p.seed_radius_m = seed_radius_m;
  p.density = density;
  p.spacing_m = std::cbrt(1.0 / density);
  p.search_radius_m = c.search_radius_spacings * p.spacing_m;
  p.plane_threshold_m = c.plane_threshold_m;
  p.plane_threshold_from_data = c.plane_threshold_from_data;
  p.pixel_size_m = 0.0;
  return p;
}

namespace {

// The density at `pixel`, falling logarithmically from `near_density` at `near_pixel` (and
// finer) to `far_density` at `far_pixel` (and coarser).
double logarithmicFall(double pixel, double near_pixel, double near_density, double far_pixel, double far_density) {
  const double t = std::clamp(std::log(pixel / near_pixel) / std::log(far_pixel / near_pixel), 0.0, 1.0);
  return near_density * std::pow(far_density / near_density, t);
}

}  // namespace

double densityForPixel(double pixel, const ParameterConstants& c, const std::optional<DataAtClick>& data) {
  if (!data || data->spacing_m <= 0.0 || data->full_density <= 0.0) {
    return logarithmicFall(pixel, c.near_pixel_m, c.max_density, c.far_pixel_m, c.min_density);
  }
  // Where a pixel is no larger than the points are apart, the user sees each point: every one.
  const double near_pixel = std::max(c.near_pixel_m, data->spacing_m);
  if (pixel <= near_pixel) return data->full_density;
  // Farther, from the data's own density down to the paper's far end. A sparse scan (points
  // farther apart than far_pixel_m) still falls over one octave of pixel size, not in a step.
  const double near_density =
      std::clamp(std::pow(data->spacing_m, -3.0), std::min(c.max_density, data->full_density), data->full_density);
  const double far_pixel = std::max(c.far_pixel_m, 2.0 * near_pixel);
  return logarithmicFall(pixel, near_pixel, near_density, far_pixel, std::min(c.min_density, near_density));
}

GrowParameters parametersForView(const ViewAtClick& view, const ParameterConstants& c,
                                 const std::optional<DataAtClick>& data) {
  const double pixel = pixelSizeAt(view);
  GrowParameters p = parametersForDensity(view.picked, densityForPixel(pixel, c, data),
                                          c.seed_fraction_of_width * pixel * view.viewport_width_px, c);
  p.pixel_size_m = pixel;
  if (data && data->spacing_m > 0.0 && data->full_density > 0.0) p.click_spacing_m = data->spacing_m;
  return p;
}

double densityForDetail(Detail detail, const ParameterConstants& c, double full_density) {
  switch (detail) {
    case Detail::kLow:
      return c.min_density;
    case Detail::kMedium:
      return std::sqrt(c.min_density * c.max_density);
    case Detail::kHigh:
      return c.max_density;
    case Detail::kFull:
      return full_density;
  }
  return full_density;
}

}  // namespace plumb::reco
