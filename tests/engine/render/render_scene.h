#pragma once
// The synthetic scenes of the render tests, as octrees built in a temporary directory, with the
// cameras that look at them.
//
// The wall scene, seen from the front (the camera at y = -10 looking along +y, z up):
//
//   z = 3  +----------------+----------------+
//          |   red wall     |   green wall   |   y = 5, 4 m wide each
//          |      +---------+------+         |
//          |      |  blue square   |         |   y = 3, x in [-1, 1], z in [1, 2]
//          |      +---------+------+         |
//   z = 0  +----------------+----------------+
//         x = -4           x = 0            x = 4
//
// Points lie on grids of kGridStep, so a picked point can be checked against the grid exactly.

#include <cmath>
#include <cstdint>
#include <string>

#include "engine/lod/octree_builder.h"
#include "engine/view/camera.h"
#include "tests/support/generated_cloud.h"
#include "tests/support/temp_directory.h"

namespace plumb::test {

constexpr double kGridStep = 0.02;  // every surface's grid starts at a multiple of it
constexpr int kWallColumns = 200;   // 4 m
constexpr int kWallRows = 150;      // 3 m
constexpr int kSquareColumns = 100, kSquareRows = 50;

// Where the scene sits in the world: far from the origin, as a scan in UTM coordinates does.
struct SceneOffset {
  double x = 0.0, y = 0.0, z = 0.0;
};

inline io::PointRecord wallScenePoint(std::uint64_t i, const SceneOffset& offset) {
  constexpr std::uint64_t kWall = std::uint64_t{kWallColumns} * kWallRows;
  constexpr std::uint16_t kFull = 65535;
  double x, y, z;
  std::array<std::uint16_t, 3> rgb{};
  if (i < 2 * kWall) {
    const std::uint64_t wall = i / kWall, j = i % kWall;
    x = -4.0 + 4.0 * static_cast<double>(wall) + kGridStep * static_cast<double>(j % kWallColumns);
    z = kGridStep * static_cast<double>(j / kWallColumns);
    y = 5.0;
    rgb = wall == 0 ? std::array<std::uint16_t, 3>{kFull, 0, 0} : std::array<std::uint16_t, 3>{0, kFull, 0};
  } else {
    const std::uint64_t j = i - 2 * kWall;
    x = -1.0 + kGridStep * static_cast<double>(j % kSquareColumns);
    z = 1.0 + kGridStep * static_cast<double>(j / kSquareColumns);
    y = 3.0;
    rgb = {0, 0, kFull};
  }
  return {x + offset.x, y + offset.y, z + offset.z, rgb, 30000};
}

inline std::uint64_t wallScenePoints() {
  return 2 * std::uint64_t{kWallColumns} * kWallRows + std::uint64_t{kSquareColumns} * kSquareRows;
}

// Builds the wall scene into `dir` and returns the octree's path.
inline std::string buildWallScene(const TempDirectory& dir, const SceneOffset& offset = {},
                                  std::uint32_t leaf_max_points = 20'000) {
  lod::BuildOptions options;
  options.sources = {
      generatedSource(wallScenePoints(), [offset](std::uint64_t i) { return wallScenePoint(i, offset); })};
  options.output = dir.file("walls.plumb");
  options.memory_mb = 64;
  options.leaf_max_points = leaf_max_points;
  lod::buildOctree(options);
  return options.output;
}

// The front view: orthographic, 4 m high, centred on x = 0, z = 1.5.
inline view::Camera wallSceneFront(int width_px, int height_px, const SceneOffset& offset = {}) {
  view::Camera camera;
  camera.projection = view::Projection::kOrthographic;
  camera.position = {offset.x, offset.y - 10.0, offset.z + 1.5};
  camera.target = {offset.x, offset.y, offset.z + 1.5};
  camera.up = {0.0, 0.0, 1.0};
  camera.ortho_height_m = 4.0;
  camera.viewport_width_px = width_px;
  camera.viewport_height_px = height_px;
  return camera;
}

// The pixel (column, row from the top) where the front view shows world (x, z).
inline std::array<int, 2> frontPixel(const view::Camera& camera, double x, double z, const SceneOffset& offset = {}) {
  const double metres_per_px = camera.ortho_height_m / camera.viewport_height_px;
  const double column = (x - (camera.position.x() - offset.x)) / metres_per_px + 0.5 * camera.viewport_width_px;
  const double row = ((camera.position.z() - offset.z) - z) / metres_per_px + 0.5 * camera.viewport_height_px;
  return {static_cast<int>(std::floor(column)), static_cast<int>(std::floor(row))};
}

}  // namespace plumb::test
