// The build's integer places (node_indexer.h) against Cube::cellAt: a cell found by shifting a
// place must be the cell of the position the place was made from, at every level, or a point
// would be indexed in one node and belong to another.

#include <gtest/gtest.h>

#include <cmath>

#include "engine/lod/cube.h"
#include "engine/lod/node_indexer.h"
#include "tests/support/generated_cloud.h"

namespace plumb::lod {
namespace {

TEST(GridPlace, CellsByShiftingAreTheCellsOfThePositionRead) {
  // An awkward cube (size and origin not powers of two), points spread over it and crowded
  // against cell boundaries of every level, where a rounding would show.
  const Cube cube{{512000.123, 5403000.77, 249.91}, 71.3};
  std::size_t tested = 0;
  for (std::uint64_t i = 0; i < 20'000; ++i) {
    Position p{};
    for (std::size_t a = 0; a < 3; ++a) p[a] = cube.origin[a] + cube.size * test::unitHash(i, a + 1);
    if (i % 2 == 1) {
      // Onto a boundary of a random level, then a few steps of a double either way.
      const auto level = static_cast<std::uint32_t>(test::unitHash(i, 7) * 24);
      const double step = cube.cellSize(level);
      for (std::size_t a = 0; a < 3; ++a) {
        const double boundary = cube.origin[a] + std::round((p[a] - cube.origin[a]) / step) * step;
        p[a] = boundary;
        for (int k = 0; k < static_cast<int>(test::unitHash(i, 8 + a) * 4); ++k) p[a] = std::nextafter(p[a], 0.0);
      }
    }
    const GridPlace place = placeOf(cube, p);
    for (std::uint32_t level = 0; level <= 30; ++level) {
      const CellKey key = cube.cellAt(p, level);
      ASSERT_EQ(cellOf(place[0], level), key.x) << "point " << i << ", level " << level;
      ASSERT_EQ(cellOf(place[1], level), key.y) << "point " << i << ", level " << level;
      ASSERT_EQ(cellOf(place[2], level), key.z) << "point " << i << ", level " << level;
      if (level > 0) {
        ASSERT_EQ(octantOf(*key.parent(), place), key.octant()) << "point " << i << ", level " << level;
      }
      ++tested;
    }
  }
  EXPECT_EQ(tested, 20'000u * 31u);
}

TEST(GridPlace, PointsOnOrBeyondTheFarFacesTakeTheLastCell) {
  const Cube cube{{10.0, 20.0, 30.0}, 8.0};
  for (const Position& p : {Position{18.0, 28.0, 38.0}, Position{18.5, 28.0 + 1e-9, 40.0}}) {
    const GridPlace place = placeOf(cube, p);
    for (std::uint32_t level : {0u, 3u, 17u, 32u}) {
      const CellKey key = cube.cellAt(p, level);
      EXPECT_EQ(cellOf(place[0], level), key.x);
      EXPECT_EQ(cellOf(place[2], level), key.z);
    }
    EXPECT_EQ(place[0], 0xFFFFFFFFu);
  }
  EXPECT_EQ(placeOf(cube, {9.0, 19.0, 29.0}), (GridPlace{0, 0, 0}));  // before the near faces
}

}  // namespace
}  // namespace plumb::lod
