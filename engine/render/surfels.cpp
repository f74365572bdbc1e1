#include "engine/render/surfels.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <Eigen/Core>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <array>
#include <cmath>

namespace plumb::render {
namespace {

constexpr std::size_t kNormalNeighbours = 12;
// Where those lie along a line (one of the scanner's, its lines far apart), a wider look.
constexpr std::size_t kWideNeighbours = 40;
constexpr int kSpacingNeighbour = 4;  // the radius: the distance to the 4th nearest
// The least ratio of the middle to the largest principal spread of a neighbourhood that spans a
// plane; below it, the neighbours lie along a line.
constexpr float kMinPlanarity = 0.05f;
// The most the spread across a neighbourhood's plane may be of the least along it: more, and
// the neighbours are no one plane (a corner, both faces of a thin wall).
constexpr float kMaxThickness = 0.2f;
// The finest grid: a node's sampling grid (octree_format.h) is 128 cells a side, its points
// about one per occupied cell.
constexpr int kMaxGridCells = 128;

// The node's points bucketed by the cells of a uniform grid over its cube: a counting sort.
class NodeGrid {
 public:
  NodeGrid(std::span<const lod::PackedPoint> points, float cell_size, int cells)
      : cells_(cells), inverse_step_(static_cast<float>(cells) / cell_size), first_(cellCount() + 1, 0) {
    std::vector<std::uint32_t> cell_of(points.size());
    for (std::size_t i = 0; i < points.size(); ++i) {
      cell_of[i] = indexOf(cellOf(points[i]));
      ++first_[cell_of[i] + 1];
    }
    for (std::size_t c = 1; c < first_.size(); ++c) first_[c] += first_[c - 1];
    order_.resize(points.size());
    std::vector<std::uint32_t> next(first_.begin(), first_.end() - 1);
    for (std::size_t i = 0; i < points.size(); ++i) order_[next[cell_of[i]]++] = static_cast<std::uint32_t>(i);
  }

  float step() const { return 1.0f / inverse_step_; }
  int cells() const { return cells_; }

  std::array<int, 3> cellOf(const lod::PackedPoint& p) const {
    const auto axis = [&](float v) { return std::clamp(static_cast<int>(v * inverse_step_), 0, cells_ - 1); };
    return {axis(p.x), axis(p.y), axis(p.z)};
  }

  // The points of a cell inside the grid.
  std::span<const std::uint32_t> at(int x, int y, int z) const {
    const std::uint32_t c = indexOf({x, y, z});
    return {order_.data() + first_[c], order_.data() + first_[c + 1]};
  }

 private:
  std::size_t cellCount() const {
    const auto side = static_cast<std::size_t>(cells_);
    return side * side * side;
  }
  std::uint32_t indexOf(const std::array<int, 3>& c) const {
    return static_cast<std::uint32_t>((c[2] * cells_ + c[1]) * cells_ + c[0]);
  }

  int cells_;
  float inverse_step_;
  std::vector<std::uint32_t> first_;  // per cell, where its points start in order_ (one more at the end)
  std::vector<std::uint32_t> order_;
};

// The nearest `capacity` neighbours found so far, ascending by squared distance.
template <std::size_t capacity>
struct Nearest {
  std::array<float, capacity> distance2;
  std::array<std::uint32_t, capacity> index;
  int count = 0;

  float worst() const { return count < static_cast<int>(capacity) ? INFINITY : distance2[capacity - 1]; }
  void offer(float d2, std::uint32_t i) {
    if (d2 >= worst()) return;
    int k = std::min(count, static_cast<int>(capacity) - 1);
    for (; k > 0 && distance2[static_cast<std::size_t>(k - 1)] > d2; --k) {
      distance2[static_cast<std::size_t>(k)] = distance2[static_cast<std::size_t>(k - 1)];
      index[static_cast<std::size_t>(k)] = index[static_cast<std::size_t>(k - 1)];
    }
    distance2[static_cast<std::size_t>(k)] = d2;
    index[static_cast<std::size_t>(k)] = i;
    count = std::min(count + 1, static_cast<int>(capacity));
  }
};

// The nearest neighbours of point i within max_radius, ring by ring of grid cells around its
// own until no cell farther out can hold a nearer one.
template <std::size_t capacity>
Nearest<capacity> nearestOf(std::span<const lod::PackedPoint> points, const NodeGrid& grid, std::uint32_t i,
                            float max_radius) {
  const lod::PackedPoint& p = points[i];
  const std::array<int, 3> home = grid.cellOf(p);
  const float max_radius2 = max_radius * max_radius;
  Nearest<capacity> nearest;
  const int max_ring = std::min(grid.cells(), static_cast<int>(std::ceil(max_radius / grid.step())) + 1);
  for (int ring = 0; ring <= max_ring; ++ring) {
    // Cells at ring r lie at least (r - 1) steps away from any point of the home cell.
    const float reach = static_cast<float>(std::max(ring - 1, 0)) * grid.step();
    if (reach * reach >= std::min(nearest.worst(), max_radius2)) break;
    for (int z = home[2] - ring; z <= home[2] + ring; ++z) {
      if (z < 0 || z >= grid.cells()) continue;
      for (int y = home[1] - ring; y <= home[1] + ring; ++y) {
        if (y < 0 || y >= grid.cells()) continue;
        const bool face = std::abs(z - home[2]) == ring || std::abs(y - home[1]) == ring;
        for (int x = home[0] - ring; x <= home[0] + ring; x += (face || ring == 0) ? 1 : 2 * ring) {
          if (x < 0 || x >= grid.cells()) continue;
          for (const std::uint32_t j : grid.at(x, y, z)) {
            if (j == i) continue;
            const lod::PackedPoint& q = points[j];
            const float dx = q.x - p.x, dy = q.y - p.y, dz = q.z - p.z;
            const float d2 = dx * dx + dy * dy + dz * dz;
            if (d2 <= max_radius2) nearest.offer(d2, j);
          }
        }
      }
    }
  }
  return nearest;
}

enum class Shape : std::uint8_t { kPlanar, kLinear, kThick };

struct Neighbourhood {
  Shape shape;
  Eigen::Vector3f normal;  // kPlanar: the plane's unit normal
};

// The principal axes of point i and its neighbours: a plane (two large spreads and a small one
// across), a line (one large spread), or neither.
template <std::size_t capacity>
Neighbourhood shapeOf(std::span<const lod::PackedPoint> points, std::size_t i, const Nearest<capacity>& nearest) {
  const auto at = [&](int k) {
    const lod::PackedPoint& q = k < 0 ? points[i] : points[nearest.index[static_cast<std::size_t>(k)]];
    return Eigen::Vector3f(q.x, q.y, q.z);
  };
  Eigen::Vector3f mean = Eigen::Vector3f::Zero();
  for (int k = -1; k < nearest.count; ++k) mean += at(k);
  mean /= static_cast<float>(nearest.count + 1);
  Eigen::Matrix3f covariance = Eigen::Matrix3f::Zero();
  for (int k = -1; k < nearest.count; ++k) {
    const Eigen::Vector3f d = at(k) - mean;
    covariance += d * d.transpose();
  }
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3f> solver;
  solver.computeDirect(covariance);
  const Eigen::Vector3f spread = solver.eigenvalues();  // ascending
  const Eigen::Vector3f normal = solver.eigenvectors().col(0).normalized();
  if (!(spread[1] > kMinPlanarity * spread[2])) return {Shape::kLinear, normal};
  if (!(spread[0] < kMaxThickness * spread[1]) || !normal.allFinite()) return {Shape::kThick, normal};
  return {Shape::kPlanar, normal};
}

}  // namespace

std::uint32_t encodeNormal(float x, float y, float z) {
  const float l1 = std::abs(x) + std::abs(y) + std::abs(z);
  float u = x / l1, v = y / l1;
  if (z < 0.0f) {
    const float fu = (1.0f - std::abs(v)) * (u >= 0.0f ? 1.0f : -1.0f);
    const float fv = (1.0f - std::abs(u)) * (v >= 0.0f ? 1.0f : -1.0f);
    u = fu;
    v = fv;
  }
  const auto snorm = [](float t) {
    return static_cast<std::uint32_t>(
        static_cast<std::uint16_t>(static_cast<std::int16_t>(std::lround(std::clamp(t, -1.0f, 1.0f) * 32767.0f))));
  };
  return snorm(u) | snorm(v) << 16;
}

void decodeNormal(std::uint32_t packed, float& x, float& y, float& z) {
  const auto unsnorm = [](std::uint32_t bits) {
    return std::max(static_cast<float>(static_cast<std::int16_t>(static_cast<std::uint16_t>(bits))) / 32767.0f, -1.0f);
  };
  x = unsnorm(packed & 0xFFFFu);
  y = unsnorm(packed >> 16);
  z = 1.0f - std::abs(x) - std::abs(y);
  if (z < 0.0f) {
    const float fx = (1.0f - std::abs(y)) * (x >= 0.0f ? 1.0f : -1.0f);
    const float fy = (1.0f - std::abs(x)) * (y >= 0.0f ? 1.0f : -1.0f);
    x = fx;
    y = fy;
  }
  const float length = std::sqrt(x * x + y * y + z * z);
  x /= length;
  y /= length;
  z /= length;
}

std::vector<Surfel> estimateSurfels(std::span<const lod::PackedPoint> own, std::span<const lod::PackedPoint> around,
                                    double cell_size, double max_radius) {
  std::vector<Surfel> surfels(own.size());
  // The node's points first, then those around it: an index below own.size() is the node's.
  std::vector<lod::PackedPoint> all(own.begin(), own.end());
  all.insert(all.end(), around.begin(), around.end());
  const std::span<const lod::PackedPoint> points(all);
  if (points.size() < 2) return surfels;
  // Cells about twice the spacing of points on one plane across the cube, so that the 27 cells
  // around a point mostly hold its 8 nearest. Points around the cube fall in its border cells.
  const double plane_spacing = cell_size / std::sqrt(static_cast<double>(points.size()));
  const int cells = std::clamp(static_cast<int>(cell_size / (2.0 * plane_spacing)), 1, kMaxGridCells);
  const NodeGrid grid(points, static_cast<float>(cell_size), cells);
  const auto max_radius_f = static_cast<float>(max_radius);

  tbb::parallel_for(
      tbb::blocked_range<std::size_t>(0, own.size(), 1024), [&](const tbb::blocked_range<std::size_t>& r) {
        for (std::size_t i = r.begin(); i != r.end(); ++i) {
          const Nearest<kNormalNeighbours> nearest =
              nearestOf<kNormalNeighbours>(points, grid, static_cast<std::uint32_t>(i), max_radius_f);
          if (nearest.count < kSpacingNeighbour) continue;  // a lone point: one pixel
          surfels[i].radius_m = std::sqrt(nearest.distance2[kSpacingNeighbour - 1]);
          Neighbourhood neighbourhood = shapeOf(points, i, nearest);
          if (neighbourhood.shape == Shape::kLinear) {
            neighbourhood = shapeOf(
                points, i, nearestOf<kWideNeighbours>(points, grid, static_cast<std::uint32_t>(i), max_radius_f));
          }
          const Eigen::Vector3f& normal = neighbourhood.normal;
          if (neighbourhood.shape == Shape::kPlanar) {
            surfels[i].normal = encodeNormal(normal.x(), normal.y(), normal.z());
          } else {
            // No plane around the point: the disc faces the eye. Where its neighbours lie along a
            // line, at half the radius: at a line's end, or along a thin edge, a whole disc would
            // stand out past it. Where they are thick (a corner, clutter, a sparse scan's noisy
            // wall) at the whole: half left a sparse real scan's walls 5.75 % open from 2 m.
            surfels[i].normal = kFacingTheEye;
            if (neighbourhood.shape == Shape::kLinear) surfels[i].radius_m *= 0.5f;
          }
        }
      });
  return surfels;
}

}  // namespace plumb::render
