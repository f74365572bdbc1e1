#include "engine/lod/cell_key.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <set>

#include "engine/lod/cube.h"

namespace plumb::lod {
namespace {

TEST(CellKey, ParentsAndChildrenAreInverse) {
  const CellKey key{5, 17, 3, 30};
  for (int octant = 0; octant < 8; ++octant) {
    const CellKey child = key.child(octant);
    EXPECT_EQ(child.level, 6u);
    EXPECT_EQ(child.parent(), key);
    EXPECT_EQ(child.octant(), octant);
    EXPECT_TRUE(key.contains(child));
    EXPECT_FALSE(child.contains(key));
  }
  EXPECT_FALSE(CellKey{}.parent().has_value());
  EXPECT_TRUE(CellKey{}.contains(key));
  EXPECT_FALSE((CellKey{1, 1, 0, 0}).contains(key));
}

TEST(CellKey, NeighboursMatchBruteForceInsideAndAtTheBoundary) {
  for (const CellKey key : {CellKey{3, 4, 4, 4}, CellKey{3, 0, 0, 0}, CellKey{3, 7, 0, 5}, CellKey{0, 0, 0, 0}}) {
    std::set<CellKey> expected;
    const std::uint32_t n = key.cellsPerAxis();
    for (std::uint32_t z = 0; z < n; ++z) {
      for (std::uint32_t y = 0; y < n; ++y) {
        for (std::uint32_t x = 0; x < n; ++x) {
          const auto far = [](std::uint32_t a, std::uint32_t b) { return (a > b ? a - b : b - a) > 1; };
          const CellKey other{key.level, x, y, z};
          if (other != key && !far(x, key.x) && !far(y, key.y) && !far(z, key.z)) expected.insert(other);
        }
      }
    }
    const auto found = key.neighbours();
    EXPECT_EQ(std::set<CellKey>(found.begin(), found.end()), expected) << key.level << " " << key.x;
    EXPECT_EQ(found.size(), expected.size());
  }
}

TEST(Cube, CellAtAndCellBoxAgree) {
  const Cube cube{{512000.0, 5403000.0, 250.0}, 64.0};
  const std::array<double, 3> p{512010.3, 5403063.999, 250.0};
  for (std::uint32_t level = 0; level < 12; ++level) {
    const CellKey key = cube.cellAt(p, level);
    const Box3 box = cube.cellBox(key);
    for (std::size_t a = 0; a < 3; ++a) {
      EXPECT_LE(box.min[a], p[a]);
      EXPECT_GE(box.max[a], p[a]);
    }
    EXPECT_EQ(cube.squaredDistance(key, p), 0.0);
  }
  // Points on the far faces belong to the last cell, not outside the cube.
  EXPECT_EQ(cube.cellAt({512064.0, 5403064.0, 314.0}, 3), (CellKey{3, 7, 7, 7}));
  EXPECT_NEAR(cube.squaredDistance(CellKey{1, 0, 0, 0}, {512000.0 + 40.0, 5403000.0, 250.0}), 64.0, 1e-9);
}

}  // namespace
}  // namespace plumb::lod
