// Point spacing measures (point_spacing.h).
//
// medianNearestDistance: hash grids (the 27 cells around a point hold every neighbour within a
// step), a strided sample, the median of the nearest distances.
// arealSpacing: the points in the plane's (tangent, bitangent) frame, relative to its centroid;
// Andrew's monotone chain for the hull (of the outermost points of thin strips, for large sets);
// the shoelace formula for its area.

#include "reco/point_spacing.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <unordered_map>
#include <vector>

#include "reco/point_grid.h"

namespace plumb::reco {

namespace {

constexpr double kGuessSpacings = 4.0;    // medianNearestDistance's first grid, in guessed spacings
constexpr std::size_t kHullStrips = 512;  // arealSpacing's hull of a large set (hullCandidates)

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

// The points of a large set that can be corners of its hull, near enough: in each of kHullStrips
// strips across x and across y, the two outermost. A corner the strips miss lies within a
// strip's width of the hull they give, so the area is off by at most the perimeter times a
// strip's width (1 / 512 of the box's side): a thousandth or so, for a sort of 2 * 4 *
// kHullStrips points instead of a seed plane's hundreds of thousands (20 ms at 100 M points).
std::vector<Eigen::Vector2d> hullCandidates(std::vector<Eigen::Vector2d> points) {
  if (points.size() <= 4 * kHullStrips) return points;
  Eigen::AlignedBox2d box;
  for (const Eigen::Vector2d& p : points) box.extend(p);
  const Eigen::Vector2d low = box.min();
  const Eigen::Vector2d extent = box.sizes().cwiseMax(Eigen::Vector2d::Constant(1e-12));
  // Per strip of each axis: the points with the least and the greatest coordinate along the other.
  std::vector<std::array<const Eigen::Vector2d*, 2>> outermost(2 * kHullStrips, {nullptr, nullptr});
  for (const Eigen::Vector2d& p : points) {
    for (int axis = 0; axis < 2; ++axis) {
      const int other = 1 - axis;
      const auto strip = std::min<std::size_t>(
          kHullStrips - 1, static_cast<std::size_t>((p[axis] - low[axis]) / extent[axis] * kHullStrips));
      auto& [least, greatest] = outermost[static_cast<std::size_t>(axis) * kHullStrips + strip];
      if (least == nullptr || p[other] < (*least)[other]) least = &p;
      if (greatest == nullptr || p[other] > (*greatest)[other]) greatest = &p;
    }
  }
  std::vector<Eigen::Vector2d> candidates;
  for (const auto& [least, greatest] : outermost) {
    if (least != nullptr) candidates.push_back(*least);
    if (greatest != nullptr) candidates.push_back(*greatest);
  }
  return candidates;
}

// The points by cell of a grid of `step`, for nearest-neighbour searches within one step. A hash
// map of lists, not GridIndex: for a few hundred searches its build is what counts, and GridIndex's
// sort took 13 ms more on a 100 M-point room's seed sphere.
class NeighbourGrid {
 public:
  NeighbourGrid(std::span<const Eigen::Vector3d> points, double step)
      : points_(points), step_(step), grid_(points.front(), step) {
    for (std::uint32_t i = 0; i < points.size(); ++i) cells_[grid_.keyOf(points[i])].push_back(i);
  }
  // The squared distance from point i to its nearest other point, if nearer than the step; else
  // the step's square.
  double nearest2(std::size_t i) const {
    double best2 = step_ * step_;
    grid_.forEachAround(points_[i], [&](const GridKey& key) {
      const auto cell = cells_.find(key);
      if (cell == cells_.end()) return;
      for (std::uint32_t j : cell->second) {
        const double d2 = (points_[j] - points_[i]).squaredNorm();
        if (d2 > 0.0 && d2 < best2) best2 = d2;
      }
    });
    return best2;
  }

 private:
  std::span<const Eigen::Vector3d> points_;
  double step_;
  PointGrid grid_;
  std::unordered_map<GridKey, std::vector<std::uint32_t>, GridKeyHash> cells_;
};

}  // namespace

double medianNearestDistance(std::span<const Eigen::Vector3d> points, double reach) {
  if (points.size() < 2) return 0.0;
  // First a grid of a few mean spacings, guessed from the points' extent (a surface across a box
  // of diagonal D has an area under D^2): its 27 cells hold a few hundred points, where cells of
  // `reach` held the whole seed sphere's (70 ms for the 287,000 points of a 100 M-point room's).
  // The rare sample with no neighbour that near is looked for again as far as `reach`.
  Eigen::AlignedBox3d box;
  for (const Eigen::Vector3d& p : points) box.extend(p);
  const double guess = kGuessSpacings * box.diagonal().norm() / std::sqrt(static_cast<double>(points.size()));
  const double step = guess > 0.0 ? std::min(reach, guess) : reach;
  const NeighbourGrid near(points, step);
  std::optional<NeighbourGrid> far;
  constexpr std::size_t kSamples = 512;
  const std::size_t stride = std::max<std::size_t>(1, points.size() / kSamples);
  std::vector<double> nearest;
  for (std::size_t i = 0; i < points.size(); i += stride) {
    double best2 = near.nearest2(i);
    if (best2 >= step * step && step < reach) {
      if (!far) far.emplace(points, reach);
      best2 = far->nearest2(i);
    }
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
  std::vector<Eigen::Vector2d> candidates = hullCandidates(std::move(projected));
  const double area = convexHullArea(candidates);
  return area > 0.0 ? std::sqrt(area / static_cast<double>(points.size())) : 0.0;
}

}  // namespace plumb::reco
