#pragma once
// How closed a rendered cloud's surfaces are (issue 24, point 3): a reference image that draws
// every point of the full-resolution cloud as a disc of its local spacing, and the share of the
// pixels inside each of its surfaces that an image under test leaves as background.
//
// The reference is what a surface "is" on screen: each point covers a disc in the plane of its
// true surface (the simulator's plane), of radius the distance to its 4th nearest neighbour (the
// spacing of the scan around it, whatever the scanner's pattern), cast exactly (a ray through
// each pixel's centre); the nearest disc wins each pixel. Its pixels carry the plane's label, so
// the measure is taken per surface, away from the surfaces' outlines (`margin_px`): holes inside
// a wall, not where one wall meets another.

#include <Eigen/Core>
#include <cstdint>
#include <span>
#include <vector>

namespace plumb::view {
struct Camera;
}

namespace plumb::test {

struct LabelledPoint {
  Eigen::Vector3d position;  // world coordinates
  std::uint32_t surface = 0;
};

struct ReferenceImage {
  static constexpr std::uint32_t kBackground = ~std::uint32_t{0};
  int width = 0, height = 0;
  std::vector<std::uint32_t> surface;  // per pixel, rows from the top: a label or kBackground
};

// Each point's local spacing: the distance to its 4th nearest other point, at most
// `max_spacing_m` (a point with fewer neighbours as near stands alone and gets that).
std::vector<float> localSpacings(std::span<const LabelledPoint> points, double max_spacing_m);

// Each point's unit normal where no truth gives it (a real scan): the least principal axis of
// the point and its 12 nearest within `max_spacing_m` (the view direction's axis, z, for a point
// with fewer than 3 neighbours there).
std::vector<Eigen::Vector3d> localNormals(std::span<const LabelledPoint> points, double max_spacing_m);

// The reference image of `points` (with their `spacings` and unit `normals`, one each) through
// `camera` (a valid one).
ReferenceImage renderReference(std::span<const LabelledPoint> points, std::span<const float> spacings,
                               std::span<const Eigen::Vector3d> normals, const view::Camera& camera);

struct SurfaceCoverage {
  std::uint64_t inside_pixels = 0;  // reference pixels at least margin_px inside their surface
  double background = 0.0;          // of those, the share the image under test leaves empty
  double worst_background = 0.0;    // the same share for the worst surface (of min_pixels or more)
  std::uint32_t worst_surface = ReferenceImage::kBackground;
  std::uint64_t surfaces_measured = 0;  // surfaces with at least min_pixels inside pixels
  double spill = 0.0;                   // image pixels with no reference surface within margin_px, per reference pixel
};

// What measureCoverage found at each pixel.
enum class PixelClass : std::uint8_t { kOther, kInsideShown, kInsideEmpty, kSpilled };

// `covered`: per pixel of the image under test (same size, rows from the top), whether a point
// shows there. `classes`, when given, receives each pixel's class.
SurfaceCoverage measureCoverage(const ReferenceImage& reference, const std::vector<bool>& covered, int margin_px,
                                std::uint64_t min_pixels, std::vector<PixelClass>* classes = nullptr);

}  // namespace plumb::test
