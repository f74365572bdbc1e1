#include "tests/support/surface_coverage.h"

#include <tbb/parallel_for.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>

#include "engine/view/camera.h"
#include "reco/grid_index.h"
#include "reco/point_grid.h"

namespace plumb::test {

std::vector<float> localSpacings(std::span<const LabelledPoint> points, double max_spacing_m) {
  std::vector<Eigen::Vector3d> positions(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) positions[i] = points[i].position;
  const Eigen::Vector3d origin = positions.empty() ? Eigen::Vector3d::Zero() : positions.front();
  const reco::PointGrid grid(origin, max_spacing_m);
  const reco::GridIndex index(grid, positions);
  std::vector<float> spacings(points.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, points.size()), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t i = r.begin(); i != r.end(); ++i) {
      // The four smallest squared distances, ascending.
      constexpr std::size_t kNeighbours = 4;
      std::array<double, kNeighbours> nearest;
      nearest.fill(max_spacing_m * max_spacing_m);
      const Eigen::Vector3d& p = positions[i];
      grid.forEachAround(p, [&](const reco::GridKey& key) {
        if (grid.squaredDistanceToCell(p, key) >= nearest.back()) return;
        for (const std::uint32_t j : index.at(key)) {
          if (j == i) continue;
          const double d = (positions[j] - p).squaredNorm();
          if (d >= nearest.back()) continue;
          std::size_t k = kNeighbours - 1;
          for (; k > 0 && nearest[k - 1] > d; --k) nearest[k] = nearest[k - 1];
          nearest[k] = d;
        }
      });
      spacings[i] = static_cast<float>(std::sqrt(nearest.back()));
    }
  });
  return spacings;
}

ReferenceImage renderReference(std::span<const LabelledPoint> points, std::span<const float> spacings,
                               std::span<const Eigen::Vector3d> normals, const view::Camera& camera) {
  ReferenceImage image;
  image.width = camera.viewport_width_px;
  image.height = camera.viewport_height_px;
  image.surface.assign(static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height),
                       ReferenceImage::kBackground);
  std::vector<double> depth(image.surface.size(), std::numeric_limits<double>::infinity());

  // Relative to the eye in double precision, so survey coordinates keep their millimetres.
  Eigen::Matrix4d view = view::viewMatrix(camera);
  view.block<3, 1>(0, 3).setZero();  // eye-relative positions: the view's rotation alone
  const Eigen::Matrix4d clip_from_eye = view::projectionMatrix(camera) * view;
  const Eigen::Matrix4d eye_from_clip = clip_from_eye.inverse();
  const Eigen::Vector3d forward = -view.row(2).head<3>().transpose();
  const auto unproject = [&](double ndc_x, double ndc_y, double ndc_z) {
    const Eigen::Vector4d p = eye_from_clip * Eigen::Vector4d(ndc_x, ndc_y, ndc_z, 1.0);
    return Eigen::Vector3d(p.head<3>() / p.w());
  };
  const double pixels_per_metre = 1.0 / view::metresPerPixel(camera, 1.0);
  const bool perspective = camera.projection == view::Projection::kPerspective;

  for (std::size_t i = 0; i < points.size(); ++i) {
    const Eigen::Vector3d p = points[i].position - camera.position;
    const double eye_depth = forward.dot(p);
    const double radius = spacings[i];
    if (eye_depth - radius < camera.near_m || eye_depth > camera.far_m) continue;
    const Eigen::Vector4d clip = clip_from_eye * p.homogeneous();
    const double x = (clip.x() / clip.w() + 1.0) * 0.5 * image.width;
    const double y = (1.0 - clip.y() / clip.w()) * 0.5 * image.height;
    // The disc lies inside the sphere of its radius: a square of that sphere's largest extent.
    const double extent = radius * pixels_per_metre / (perspective ? eye_depth - radius : 1.0) * 1.5 + 1.0;
    const int low_x = std::max(0, static_cast<int>(std::floor(x - extent)));
    const int high_x = std::min(image.width - 1, static_cast<int>(std::floor(x + extent)));
    const int low_y = std::max(0, static_cast<int>(std::floor(y - extent)));
    const int high_y = std::min(image.height - 1, static_cast<int>(std::floor(y + extent)));
    const auto own_x = static_cast<int>(std::floor(x)), own_y = static_cast<int>(std::floor(y));
    const Eigen::Vector3d& n = normals[points[i].surface];
    for (int row = low_y; row <= high_y; ++row) {
      for (int column = low_x; column <= high_x; ++column) {
        const double ndc_x = 2.0 * (column + 0.5) / image.width - 1.0;
        const double ndc_y = 1.0 - 2.0 * (row + 0.5) / image.height;
        double pixel_depth = eye_depth;
        if (column != own_x || row != own_y) {
          // The ray through the pixel's centre, to the disc's plane.
          const Eigen::Vector3d from = unproject(ndc_x, ndc_y, -1.0);
          const Eigen::Vector3d direction = unproject(ndc_x, ndc_y, 1.0) - from;
          const double facing = n.dot(direction);
          if (std::abs(facing) < 1e-12) continue;
          const Eigen::Vector3d hit = from + n.dot(p - from) / facing * direction;
          if ((hit - p).squaredNorm() > radius * radius) continue;
          pixel_depth = forward.dot(hit);
          if (pixel_depth < camera.near_m) continue;
        }
        const std::size_t at =
            static_cast<std::size_t>(row) * static_cast<std::size_t>(image.width) + static_cast<std::size_t>(column);
        if (pixel_depth < depth[at]) {
          depth[at] = pixel_depth;
          image.surface[at] = points[i].surface;
        }
      }
    }
  }
  return image;
}

SurfaceCoverage measureCoverage(const ReferenceImage& reference, const std::vector<bool>& covered, int margin_px,
                                std::uint64_t min_pixels, std::vector<PixelClass>* classes) {
  const int width = reference.width, height = reference.height;
  const auto at = [&](int column, int row) {
    return static_cast<std::size_t>(row) * static_cast<std::size_t>(width) + static_cast<std::size_t>(column);
  };
  struct Count {
    std::uint64_t inside = 0, empty = 0;
  };
  std::map<std::uint32_t, Count> surfaces;
  std::uint64_t reference_pixels = 0, spilled = 0;
  if (classes != nullptr) classes->assign(reference.surface.size(), PixelClass::kOther);
  for (int row = 0; row < height; ++row) {
    for (int column = 0; column < width; ++column) {
      const std::uint32_t label = reference.surface[at(column, row)];
      if (label != ReferenceImage::kBackground) ++reference_pixels;
      // The window of margin_px around the pixel: all one surface (inside it) or no surface at all.
      bool all_same = true, any_surface = false;
      for (int dy = -margin_px; dy <= margin_px; ++dy) {
        for (int dx = -margin_px; dx <= margin_px; ++dx) {
          const int c = std::clamp(column + dx, 0, width - 1), r = std::clamp(row + dy, 0, height - 1);
          const std::uint32_t other = reference.surface[at(c, r)];
          all_same = all_same && other == label;
          any_surface = any_surface || other != ReferenceImage::kBackground;
        }
      }
      const bool shown = covered[at(column, row)];
      PixelClass found = PixelClass::kOther;
      if (label != ReferenceImage::kBackground && all_same) {
        Count& count = surfaces[label];
        ++count.inside;
        if (!shown) ++count.empty;
        found = shown ? PixelClass::kInsideShown : PixelClass::kInsideEmpty;
      }
      if (shown && !any_surface) {
        ++spilled;
        found = PixelClass::kSpilled;
      }
      if (classes != nullptr) (*classes)[at(column, row)] = found;
    }
  }
  SurfaceCoverage coverage;
  std::uint64_t empty = 0;
  for (const auto& [label, count] : surfaces) {
    coverage.inside_pixels += count.inside;
    empty += count.empty;
    if (count.inside < min_pixels) continue;
    ++coverage.surfaces_measured;
    const double share = static_cast<double>(count.empty) / static_cast<double>(count.inside);
    if (coverage.worst_surface == ReferenceImage::kBackground || share > coverage.worst_background) {
      coverage.worst_background = share;
      coverage.worst_surface = label;
    }
  }
  if (coverage.inside_pixels > 0) {
    coverage.background = static_cast<double>(empty) / static_cast<double>(coverage.inside_pixels);
  }
  if (reference_pixels > 0) coverage.spill = static_cast<double>(spilled) / static_cast<double>(reference_pixels);
  return coverage;
}

}  // namespace plumb::test
