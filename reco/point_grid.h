#pragma once
// A uniform hash grid over positions near an origin: the neighbour search of the region grower.
// With a step equal to the search radius, the 27 grid cells around a point hold every point
// within one step of it.

#include <Eigen/Core>
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

class PointGrid {
 public:
  // Positions are taken relative to `origin` (the seed): UTM coordinates divided by a few
  // centimetres would still fit, relative ones keep the hash well spread.
  PointGrid(const Eigen::Vector3d& origin, double step) : origin_(origin), inverse_(1.0 / step) {}

  GridKey keyOf(const Eigen::Vector3d& p) const {
    const Eigen::Vector3d g = (p - origin_) * inverse_;
    return {static_cast<std::int64_t>(std::floor(g.x())), static_cast<std::int64_t>(std::floor(g.y())),
            static_cast<std::int64_t>(std::floor(g.z()))};
  }

  // Calls visit(key) for the 27 grid cells around p's cell: all that can hold points within one
  // step of p.
  template <typename Visit>
  void forEachAround(const Eigen::Vector3d& p, Visit&& visit) const {
    const GridKey k = keyOf(p);
    for (std::int64_t dz = -1; dz <= 1; ++dz) {
      for (std::int64_t dy = -1; dy <= 1; ++dy) {
        for (std::int64_t dx = -1; dx <= 1; ++dx) visit(GridKey{k.x + dx, k.y + dy, k.z + dz});
      }
    }
  }

 private:
  Eigen::Vector3d origin_;
  double inverse_;
};

}  // namespace plumb::reco
