#pragma once
// Automatic parameter estimation (paper section 3.7): the region grower's parameters from what
// the user sees. Moving the camera closer to a place raises the detail of its reconstruction.
// docs/parameters.md explains the constants.

#include <Eigen/Core>
#include <optional>

namespace plumb::reco {

// What the camera shows when the user clicks: OpenGL-style matrices (the camera looks down its
// -z axis; clip space from the projection), the viewport in pixels, and the picked point.
struct ViewAtClick {
  Eigen::Matrix4d view = Eigen::Matrix4d::Identity();        // world -> camera
  Eigen::Matrix4d projection = Eigen::Matrix4d::Identity();  // camera -> clip (perspective or orthographic)
  double viewport_width_px = 1920.0;
  double viewport_height_px = 1080.0;
  Eigen::Vector3d picked = Eigen::Vector3d::Zero();  // world coordinates, double precision
};

// The constants of the mapping, all configurable; the defaults follow the paper.
struct ParameterConstants {
  double seed_fraction_of_width = 0.10;  // r_s: this share of the screen width at the picked depth
  // d falls logarithmically from max_density (pixels of near_pixel_m or smaller) to min_density
  // (pixels of far_pixel_m or larger), in points per cubic metre.
  double max_density = 10'000.0;
  double min_density = 100.0;
  double near_pixel_m = 0.0005;         // 0.5 mm per pixel: a wall seen from about half a metre
  double far_pixel_m = 0.02;            // 20 mm per pixel: a facade seen from about 40 m
  double search_radius_spacings = 2.0;  // r: this many mean point spacings at density d
  double plane_threshold_m = 0.02;      // t_p: the user's precision setting
  // Whether t_p follows the noise measured on the seed planes (noise_threshold.h), starting
  // from plane_threshold_m; false when the user sets t_p.
  bool plane_threshold_from_data = true;
};

// The cloud at a click (measured by dataAtClick, data_at_click.h): how far apart its points lie
// there, and the density of the octree's deepest level (every point; --detail full).
struct DataAtClick {
  double spacing_m = 0.0;
  double full_density = 0.0;
};

struct GrowParameters {
  Eigen::Vector3d seed;      // p_0, the picked point
  double seed_radius_m;      // r_s
  double density;            // d, points per cubic metre
  double spacing_m;          // the mean point spacing at density d: d^(-1/3)
  double search_radius_m;    // r
  double plane_threshold_m;  // t_p, or where plane_threshold_from_data the start of its estimate
  bool plane_threshold_from_data = false;
  double pixel_size_m;  // the projected size of a pixel at the picked point, for display
  // The data's spacing at the click that d followed (DataAtClick); 0 where d came from the
  // paper's mapping alone or from a detail level.
  double click_spacing_m = 0.0;
};

// The view of a 60-degree perspective camera on a 1920 x 1080 screen looking at `picked` from
// `distance` metres: what the viewer shows when the user clicks there from that far (the
// --view-distance of plumb grow).
ViewAtClick viewFromDistance(const Eigen::Vector3d& picked, double distance);

// The parameters for a click. The picked point must lie in front of a perspective camera.
// Without `data`, d follows the paper's mapping alone (max_density at near_pixel_m down to
// min_density at far_pixel_m). With it, detail follows the data: every point where the pixel is
// as fine as the data's spacing or finer (or near_pixel_m, a wall from half a metre), and the
// logarithmic fall from the data's own density there to min_density at far_pixel_m (or at twice
// the data's spacing where that is farther). It never asks for fewer points than the paper's.
GrowParameters parametersForView(const ViewAtClick& view, const ParameterConstants& constants = {},
                                 const std::optional<DataAtClick>& data = std::nullopt);

// d for a pixel of `pixel_m` at the click, as parametersForView maps it.
double densityForPixel(double pixel_m, const ParameterConstants& constants, const std::optional<DataAtClick>& data);

// The parameters for a wanted density (the --detail and --view-distance paths of plumb grow).
GrowParameters parametersForDensity(const Eigen::Vector3d& seed, double density, double seed_radius_m,
                                    const ParameterConstants& constants = {});

// The detail levels that override what the view implies (plumb grow --detail, the viewer's
// Grow panel): low, medium and high are the paper's far, middle (geometric mean) and near
// densities, whatever the data; full is every point of the octree (`full_density`, its finest
// level's).
enum class Detail { kLow, kMedium, kHigh, kFull };
double densityForDetail(Detail detail, const ParameterConstants& constants, double full_density);

// The size of a pixel at the picked point, metres (perspective: grows with depth; orthographic:
// constant).
double pixelSizeAt(const ViewAtClick& view);

}  // namespace plumb::reco
