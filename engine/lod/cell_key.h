#pragma once
// Octree cells addressed by (level, ix, iy, iz) in a cube around the cloud (paper section 3.1,
// after Yoder et al.'s indexing): level 0 is the whole cube; a cell at level L has integer
// coordinates in [0, 2^L) along each axis. Parents, children and neighbours are integer
// arithmetic, no tree walk.

#include <array>
#include <compare>
#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

namespace plumb::lod {

// The deepest level a cell may have: 2^30 cells per axis keep a 1000 km cube at 1 mm.
constexpr int kMaxLevel = 30;

struct CellKey {
  std::uint32_t level = 0;
  std::uint32_t x = 0, y = 0, z = 0;

  auto operator<=>(const CellKey&) const = default;

  std::uint32_t cellsPerAxis() const { return std::uint32_t{1} << level; }
  bool valid() const { return level <= kMaxLevel && x < cellsPerAxis() && y < cellsPerAxis() && z < cellsPerAxis(); }

  // The enclosing cell one level up; the root has none.
  std::optional<CellKey> parent() const {
    if (level == 0) return std::nullopt;
    return CellKey{level - 1, x >> 1, y >> 1, z >> 1};
  }

  // Child `octant` (bit 0: +x half, bit 1: +y, bit 2: +z).
  CellKey child(int octant) const {
    const auto o = static_cast<std::uint32_t>(octant);
    return {level + 1, (x << 1) | (o & 1u), (y << 1) | ((o >> 1) & 1u), (z << 1) | ((o >> 2) & 1u)};
  }
  std::array<CellKey, 8> children() const {
    std::array<CellKey, 8> result;
    for (int octant = 0; octant < 8; ++octant) result[static_cast<std::size_t>(octant)] = child(octant);
    return result;
  }
  // Which child of its parent this cell is.
  int octant() const { return static_cast<int>((x & 1u) | ((y & 1u) << 1) | ((z & 1u) << 2)); }

  // Whether `other` is this cell or lies inside it.
  bool contains(const CellKey& other) const {
    if (other.level < level) return false;
    const std::uint32_t shift = other.level - level;
    return (other.x >> shift) == x && (other.y >> shift) == y && (other.z >> shift) == z;
  }

  // The up to 26 cells of the same level that share a face, an edge or a corner with this one
  // (fewer at the cube's boundary).
  std::vector<CellKey> neighbours() const {
    std::vector<CellKey> result;
    result.reserve(26);
    const auto n = static_cast<std::int64_t>(cellsPerAxis());
    for (int dz = -1; dz <= 1; ++dz) {
      for (int dy = -1; dy <= 1; ++dy) {
        for (int dx = -1; dx <= 1; ++dx) {
          if (dx == 0 && dy == 0 && dz == 0) continue;
          const std::int64_t nx = std::int64_t{x} + dx, ny = std::int64_t{y} + dy, nz = std::int64_t{z} + dz;
          if (nx < 0 || ny < 0 || nz < 0 || nx >= n || ny >= n || nz >= n) continue;
          result.push_back(
              {level, static_cast<std::uint32_t>(nx), static_cast<std::uint32_t>(ny), static_cast<std::uint32_t>(nz)});
        }
      }
    }
    return result;
  }
};

struct CellKeyHash {
  std::size_t operator()(const CellKey& key) const {
    std::uint64_t h = key.level;
    h = h * 0x9E3779B97F4A7C15ULL ^ key.x;
    h = h * 0x9E3779B97F4A7C15ULL ^ key.y;
    h = h * 0x9E3779B97F4A7C15ULL ^ key.z;
    return static_cast<std::size_t>(h ^ (h >> 29));
  }
};

}  // namespace plumb::lod
