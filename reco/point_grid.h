#pragma once
// A uniform hash grid over positions near an origin: the neighbour search of the region grower.
// With a step equal to the search radius, the 27 grid cells around a point hold every point
// within one step of it.

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

namespace plumb::reco {

struct GridKey {
  std::int64_t x, y, z;
  bool operator==(const GridKey&) const = default;
};

struct GridKeyHash {
  std::size_t operator()(const GridKey& k) const {
    return static_cast<std::size_t>((static_cast<std::uint64_t>(k.x) * 73856093ULL) ^
                                    (static_cast<std::uint64_t>(k.y) * 19349663ULL) ^
                                    (static_cast<std::uint64_t>(k.z) * 83492791ULL));
  }
};

// GridKeyHash with its entropy moved into the low bits, for tables that keep the low bits of a
// hash (open addressing with a power-of-two size).
inline std::size_t lowBitsHash(const GridKey& key) {
  return static_cast<std::size_t>((GridKeyHash{}(key)*0x9E3779B97F4A7C15ULL) >> 17);
}

struct GridKeyLowBitsHash {
  std::size_t operator()(const GridKey& key) const { return lowBitsHash(key); }
};

class PointGrid {
 public:
  // Positions are taken relative to `origin` (the seed): UTM coordinates divided by a few
  // centimetres would still fit, relative ones keep the hash well spread.
  PointGrid(const Eigen::Vector3d& origin, double step) : origin_(origin), inverse_(1.0 / step) {}

  const Eigen::Vector3d& origin() const { return origin_; }

  GridKey keyOf(const Eigen::Vector3d& p) const {
    const Eigen::Vector3d g = (p - origin_) * inverse_;
    return {static_cast<std::int64_t>(std::floor(g.x())), static_cast<std::int64_t>(std::floor(g.y())),
            static_cast<std::int64_t>(std::floor(g.z()))};
  }

  // Calls visit(key) for the 27 grid cells around p's cell: all that can hold points within one
  // step of p. p's own cell comes first, where a search for the nearest point is likeliest to
  // find it and can then skip the cells farther than that (squaredDistanceToCell).
  template <typename Visit>
  void forEachAround(const Eigen::Vector3d& p, Visit&& visit) const {
    const GridKey k = keyOf(p);
    visit(k);
    for (std::int64_t dz = -1; dz <= 1; ++dz) {
      for (std::int64_t dy = -1; dy <= 1; ++dy) {
        for (std::int64_t dx = -1; dx <= 1; ++dx) {
          if (dx != 0 || dy != 0 || dz != 0) visit(GridKey{k.x + dx, k.y + dy, k.z + dz});
        }
      }
    }
  }

  // Calls visit(key) for the cells of forEachAround, in its order, that reach within `reach` (at
  // most one step) of p: a search within the step passes over the cells only their corners or
  // edges bring near (on average 20.6 of the 27 are left). A cell is passed over
  // only where it lies a thousandth farther than `reach`, so that a point the caller measures in
  // single precision at `reach` is never lost to the rounding.
  template <typename Visit>
  void forEachAroundWithin(const Eigen::Vector3d& p, double reach, Visit&& visit) const {
    const Eigen::Vector3d g = (p - origin_) * inverse_;
    const GridKey k{static_cast<std::int64_t>(std::floor(g.x())), static_cast<std::int64_t>(std::floor(g.y())),
                    static_cast<std::int64_t>(std::floor(g.z()))};
    // Per axis, the squared gap (in steps) to the neighbour below, to p's own layer and above.
    std::array<std::array<double, 3>, 3> gap2{};
    const std::array<std::int64_t, 3> cell{k.x, k.y, k.z};
    for (std::size_t a = 0; a < 3; ++a) {
      const double within = g[static_cast<Eigen::Index>(a)] - static_cast<double>(cell[a]);
      gap2[a] = {within * within, 0.0, (1.0 - within) * (1.0 - within)};
    }
    const double limit = reach * inverse_ * 1.001;
    const double limit2 = limit * limit;
    visit(k);
    for (std::int64_t dz = -1; dz <= 1; ++dz) {
      for (std::int64_t dy = -1; dy <= 1; ++dy) {
        const double row2 = gap2[2][static_cast<std::size_t>(dz + 1)] + gap2[1][static_cast<std::size_t>(dy + 1)];
        if (row2 > limit2) continue;
        for (std::int64_t dx = -1; dx <= 1; ++dx) {
          if (dx == 0 && dy == 0 && dz == 0) continue;
          if (row2 + gap2[0][static_cast<std::size_t>(dx + 1)] > limit2) continue;
          visit(GridKey{k.x + dx, k.y + dy, k.z + dz});
        }
      }
    }
  }

  // Calls visit(key) for the 2 x 2 x 2 grid cells nearest p: p's own cell and, along each axis,
  // the neighbour on the side of p's nearer face. They hold every point within half a step of p.
  template <typename Visit>
  void forEachNear(const Eigen::Vector3d& p, Visit&& visit) const {
    const Eigen::Vector3d g = (p - origin_) * inverse_;
    std::array<std::int64_t, 3> low{};
    for (int a = 0; a < 3; ++a) {
      const double cell = std::floor(g[a]);
      low[static_cast<std::size_t>(a)] = static_cast<std::int64_t>(cell) - (g[a] - cell < 0.5 ? 1 : 0);
    }
    for (std::int64_t dz = 0; dz <= 1; ++dz) {
      for (std::int64_t dy = 0; dy <= 1; ++dy) {
        for (std::int64_t dx = 0; dx <= 1; ++dx) visit(GridKey{low[0] + dx, low[1] + dy, low[2] + dz});
      }
    }
  }
  // The corner of grid cell `key` with the smallest coordinates; the cell is one step wide.
  Eigen::Vector3d cellMin(const GridKey& key) const {
    return origin_ +
           Eigen::Vector3d(static_cast<double>(key.x), static_cast<double>(key.y), static_cast<double>(key.z)) /
               inverse_;
  }

  // The squared distance from p to the nearest point of grid cell `key` (0 inside it).
  double squaredDistanceToCell(const Eigen::Vector3d& p, const GridKey& key) const {
    const Eigen::Vector3d g = (p - origin_) * inverse_;
    const std::array<double, 3> low{static_cast<double>(key.x), static_cast<double>(key.y), static_cast<double>(key.z)};
    double sum = 0.0;
    for (int a = 0; a < 3; ++a) {
      const double below = low[static_cast<std::size_t>(a)] - g[a];
      const double above = g[a] - (low[static_cast<std::size_t>(a)] + 1.0);
      const double gap = std::max({below, above, 0.0});
      sum += gap * gap;
    }
    return sum / (inverse_ * inverse_);
  }

 private:
  Eigen::Vector3d origin_;
  double inverse_;
};

}  // namespace plumb::reco
