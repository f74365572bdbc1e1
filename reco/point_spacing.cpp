// Point spacing measures (point_spacing.h).
//
// medianNearestDistance: a hash grid of step `reach` (the 27 cells around a point hold every
// neighbour within reach), a strided sample, the median of the nearest distances.
// arealSpacing: the points in the plane's (tangent, bitangent) frame, relative to its centroid;
// Andrew's monotone chain for the hull; the shoelace formula for its area.

#include "reco/point_spacing.h"

#include <algorithm>
#include <cmath>
#include <unordered_map>
#include <vector>

#include "reco/point_grid.h"

namespace plumb::reco {
namespace {

double cross(const Eigen::Vector2d& o, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  const Eigen::Vector2d u = a - o, v = b - o;
  return u.x() * v.y() - u.y() * v.x();
}

// The area of the convex hull of `points` (sorted in place).
double convexHullArea(std::vector<Eigen::Vector2d>& points) {
  std::sort(points.begin(), points.end(), [](const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return a.x() != b.x() ? a.x() < b.x() : a.y() < b.y();
  });
  std::vector<Eigen::Vector2d> hull(2 * points.size());
  std::size_t k = 0;
  for (const Eigen::Vector2d& p : points) {  // lower chain
    while (k >= 2 && cross(hull[k - 2], hull[k - 1], p) <= 0.0) --k;
    hull[k++] = p;
  }
  for (std::size_t i = points.size() - 1, lower = k + 1; i-- > 0;) {  // upper chain
    while (k >= lower && cross(hull[k - 2], hull[k - 1], points[i]) <= 0.0) --k;
    hull[k++] = points[i];
  }
  double twice_area = 0.0;
  for (std::size_t i = 0; i + 1 < k; ++i) twice_area += hull[i].x() * hull[i + 1].y() - hull[i + 1].x() * hull[i].y();
  return 0.5 * std::abs(twice_area);
}

}  // namespace

double medianNearestDistance(std::span<const Eigen::Vector3d> points, double reach) {
  if (points.size() < 2) return 0.0;
  const PointGrid grid(points.front(), reach);
  std::unordered_map<GridKey, std::vector<std::uint32_t>, GridKeyHash> cells;
  for (std::uint32_t i = 0; i < points.size(); ++i) cells[grid.keyOf(points[i])].push_back(i);
  constexpr std::size_t kSamples = 512;
  const std::size_t stride = std::max<std::size_t>(1, points.size() / kSamples);
  std::vector<double> nearest;
  for (std::size_t i = 0; i < points.size(); i += stride) {
    double best2 = reach * reach;
    grid.forEachAround(points[i], [&](const GridKey& key) {
      const auto it = cells.find(key);
      if (it == cells.end()) return;
      for (std::uint32_t j : it->second) {
        const double d2 = (points[j] - points[i]).squaredNorm();
        if (d2 > 0.0 && d2 < best2) best2 = d2;
      }
    });
    nearest.push_back(std::sqrt(best2));
  }
  const auto middle = nearest.begin() + static_cast<std::ptrdiff_t>(nearest.size() / 2);
  std::nth_element(nearest.begin(), middle, nearest.end());
  return *middle;
}

double arealSpacing(const Plane& plane, std::span<const Eigen::Vector3d> points) {
  if (points.size() < 3) return 0.0;
  std::vector<Eigen::Vector2d> projected;
  projected.reserve(points.size());
  for (const Eigen::Vector3d& p : points) {
    const Eigen::Vector3d d = p - plane.centroid;
    projected.emplace_back(d.dot(plane.tangent), d.dot(plane.bitangent));
  }
  const double area = convexHullArea(projected);
  return area > 0.0 ? std::sqrt(area / static_cast<double>(points.size())) : 0.0;
}

}  // namespace plumb::reco
