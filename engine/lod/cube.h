#pragma once
// The cube the octree divides: a double-precision origin (its minimum corner) and edge length,
// so that cells far from the world origin (UTM coordinates) keep full precision.

#include <algorithm>
#include <array>
#include <cmath>

#include "engine/lod/cell_key.h"

namespace plumb::lod {

struct Box3 {
  std::array<double, 3> min, max;
};

struct Cube {
  std::array<double, 3> origin{0, 0, 0};
  double size = 1.0;

  double cellSize(std::uint32_t level) const { return std::ldexp(size, -static_cast<int>(level)); }

  Box3 cellBox(const CellKey& key) const {
    const double s = cellSize(key.level);
    return {{origin[0] + key.x * s, origin[1] + key.y * s, origin[2] + key.z * s},
            {origin[0] + (key.x + 1.0) * s, origin[1] + (key.y + 1.0) * s, origin[2] + (key.z + 1.0) * s}};
  }
  std::array<double, 3> cellMin(const CellKey& key) const { return cellBox(key).min; }

  // The cell of `level` holding point p (clamped into the cube, so points on the far faces
  // belong to the last cell). The one rule for which cell a point lies in: every level scales
  // the same product (p - origin) * (1 / size) by a power of two, exactly, so a point's cell at
  // one level is always the parent of its cell at the next.
  CellKey cellAt(const std::array<double, 3>& p, std::uint32_t level) const {
    const auto n = static_cast<double>(std::uint64_t{1} << level);
    const double scale = n / size;  // = 2^level * (1 / size), rounded once
    std::array<std::uint32_t, 3> index{};
    for (std::size_t a = 0; a < 3; ++a) {
      const double cell = std::floor((p[a] - origin[a]) * scale);
      index[a] = static_cast<std::uint32_t>(std::clamp(cell, 0.0, n - 1.0));
    }
    return {level, index[0], index[1], index[2]};
  }

  // The smallest squared distance from p to the box of `key` (0 inside).
  double squaredDistance(const CellKey& key, const std::array<double, 3>& p) const {
    const Box3 box = cellBox(key);
    double sum = 0.0;
    for (std::size_t a = 0; a < 3; ++a) {
      const double d = std::max({box.min[a] - p[a], 0.0, p[a] - box.max[a]});
      sum += d * d;
    }
    return sum;
  }
};

}  // namespace plumb::lod
