#include "tests/support/surface_coverage.h"

#include <tbb/parallel_for.h>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <utility>

#include "engine/view/camera.h"
#include "reco/grid_index.h"
#include "reco/point_grid.h"

namespace plumb::test {

namespace {

// Calls visit(i, neighbours) for each point with the indices of its (at most) `k` nearest other
// points within `max_distance_m`, nearest first.
template <typename Visit>
void forEachNeighbourhood(std::span<const LabelledPoint> points, double max_distance_m, std::size_t k, Visit&& visit) {
  std::vector<Eigen::Vector3d> positions(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) positions[i] = points[i].position;
  const Eigen::Vector3d origin = positions.empty() ? Eigen::Vector3d::Zero() : positions.front();
  const reco::PointGrid grid(origin, max_distance_m);
  const reco::GridIndex index(grid, positions);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, points.size()), [&](const tbb::blocked_range<std::size_t>& r) {
    std::vector<std::pair<double, std::uint32_t>> nearest;  // (squared distance, index), ascending
    for (std::size_t i = r.begin(); i != r.end(); ++i) {
      nearest.clear();
      const Eigen::Vector3d& p = positions[i];
      const auto worst = [&] { return nearest.size() < k ? max_distance_m * max_distance_m : nearest.back().first; };
      grid.forEachAround(p, [&](const reco::GridKey& key) {
        if (grid.squaredDistanceToCell(p, key) >= worst()) return;
        for (const std::uint32_t j : index.at(key)) {
          if (j == i) continue;
          const double d = (positions[j] - p).squaredNorm();
          if (d >= worst()) continue;
          nearest.insert(std::upper_bound(nearest.begin(), nearest.end(), std::make_pair(d, j)), {d, j});
          if (nearest.size() > k) nearest.pop_back();
        }
      });
      visit(i, std::span<const std::pair<double, std::uint32_t>>(nearest));
    }
  });
}

}  // namespace

std::vector<float> localSpacings(std::span<const LabelledPoint> points, double max_spacing_m) {
  std::vector<float> spacings(points.size());
  forEachNeighbourhood(points, max_spacing_m, 4, [&](std::size_t i, auto nearest) {
    spacings[i] = static_cast<float>(nearest.size() < 4 ? max_spacing_m : std::sqrt(nearest.back().first));
  });
  return spacings;
}

std::vector<Eigen::Vector3d> localNormals(std::span<const LabelledPoint> points, double max_spacing_m) {
  std::vector<Eigen::Vector3d> normals(points.size(), Eigen::Vector3d::UnitZ());
  forEachNeighbourhood(points, max_spacing_m, 12, [&](std::size_t i, auto nearest) {
    if (nearest.size() < 3) return;
    Eigen::Vector3d mean = points[i].position;
    for (const auto& [d, j] : nearest) mean += points[j].position;
    mean /= static_cast<double>(nearest.size() + 1);
    Eigen::Matrix3d covariance = (points[i].position - mean) * (points[i].position - mean).transpose();
    for (const auto& [d, j] : nearest)
      covariance += (points[j].position - mean) * (points[j].position - mean).transpose();
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(covariance);
    normals[i] = solver.eigenvectors().col(0).normalized();
  });
  return normals;
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
  // The ray through a pixel's centre, from the near plane to the far one: both ends are affine
  // in the pixel's column and row, under either projection.
  const auto rayEnd = [&](double column, double row, double ndc_z) {
    return unproject(2.0 * (column + 0.5) / image.width - 1.0, 1.0 - 2.0 * (row + 0.5) / image.height, ndc_z);
  };
  const Eigen::Vector3d from0 = rayEnd(0, 0, -1.0), from_dx = rayEnd(1, 0, -1.0) - from0,
                        from_dy = rayEnd(0, 1, -1.0) - from0;
  const Eigen::Vector3d to0 = rayEnd(0, 0, 1.0), to_dx = rayEnd(1, 0, 1.0) - to0, to_dy = rayEnd(0, 1, 1.0) - to0;

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
    const Eigen::Vector3d& n = normals[i];
    for (int row = low_y; row <= high_y; ++row) {
      for (int column = low_x; column <= high_x; ++column) {
        double pixel_depth = eye_depth;
        if (column != own_x || row != own_y) {
          // The ray through the pixel's centre, to the disc's plane.
          const Eigen::Vector3d from = from0 + column * from_dx + row * from_dy;
          const Eigen::Vector3d direction = to0 + column * to_dx + row * to_dy - from;
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
