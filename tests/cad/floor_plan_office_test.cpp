// The floor plan of the simulated office (issue 22, point 3): a 16 x 2 m corridor and three
// offices, each room's walls grown from a click and cut at 2.4 m. Label accuracy, Release builds
// only (tests/CMakeLists.txt): 600,000 points and 16 grows take 4 s there, 3 minutes under ASan.

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

#include "cad/floor_plan.h"
#include "tests/cad/grown_walls.h"

namespace plumb::cad {
namespace {

using test::GrownWalls;
using test::kOffset;
using test::TrueWall;

// The office (docs/simulator.md): a 16 x 2 m corridor and three offices beside it, behind walls
// 0.15 m thick. Each room's four walls, clicked at 2.3 m, above the doors and windows.
std::vector<TrueWall> officeWalls() {
  std::vector<TrueWall> walls{
      {{0.0, 1.0, 2.3}, 0, 0.0}, {{16.0, 1.0, 2.3}, 0, 16.0}, {{8.0, 0.0, 2.3}, 1, 0.0}, {{8.0, 2.0, 2.3}, 1, 2.0}};
  const std::array<double, 3> min_x{0.0, 5.35, 10.8}, max_x{5.2, 10.65, 16.0};
  for (std::size_t i = 0; i < 3; ++i) {
    walls.push_back({{min_x[i], 4.5, 2.3}, 0, min_x[i]});
    walls.push_back({{max_x[i], 4.5, 2.3}, 0, max_x[i]});
    walls.push_back({{min_x[i] + 3.0, 2.15, 2.3}, 1, 2.15});
    walls.push_back({{min_x[i] + 2.5, 7.0, 2.3}, 1, 7.0});
  }
  return walls;
}

// Cut at 2.4 m: every line on its true wall within 2 mm, the walls between the rooms 0.15 m
// thick within 2 mm, and every room closed. The offices' coplanar walls come out as one segment
// each side (the grower carries a face past a partition's end into the next office), which the
// plan cuts where it runs through a wall. The corridor's long walls, seen from its one station at
// grazing angles, grow only to 2.75 m from its ends at this detail, farther than the join gap: they
// reach its end walls across the empty gaps (join_reach_m).
TEST(FloorPlanOfGrownWalls, EveryRoomCloses) {
  const GrownWalls grown = grownWalls("office", 600'000, officeWalls());
  const FloorPlan plan = floorPlanAt(grown.project, {.height_m = kOffset.z() + 2.4});
  expectLinesOnTheirWalls(plan, grown.walls, 0.002);
  std::size_t closed = 0;
  for (const PlanChain& chain : plan.chains) closed += chain.closed ? 1u : 0u;
  std::printf("%zu wall faces, %zu lines, %zu joins, %zu chains, %zu closed, %zu walls paired\n", plan.wall_faces,
              plan.lines.size(), plan.joins, plan.chains.size(), closed, plan.walls.size());
  for (const PlanWall& wall : plan.walls) {
    std::printf("wall of %llu and %llu: %.2f mm\n", static_cast<unsigned long long>(wall.face_a),
                static_cast<unsigned long long>(wall.face_b), wall.thickness_m * 1e3);
    EXPECT_NEAR(wall.thickness_m, 0.15, 0.002);
  }
  EXPECT_EQ(closed, 4u) << "the three offices and the corridor";
  // The corridor's wall and the offices' (one segment), and the two walls between offices.
  EXPECT_EQ(plan.walls.size(), 3u);
  std::size_t corridors = 0;
  for (const PlanChain& chain : plan.chains) {
    if (!chain.closed) continue;
    ASSERT_EQ(chain.vertices.size(), 4u);
    Eigen::Vector3d low = chain.vertices[0], high = chain.vertices[0];
    for (const Eigen::Vector3d& v : chain.vertices) {
      low = low.cwiseMin(v);
      high = high.cwiseMax(v);
    }
    const Eigen::Vector3d size = high - low;
    std::printf("a closed room %.4f x %.4f m\n", size.x(), size.y());
    if (std::abs(size.y() - 2.0) < 0.002) {
      // The corridor: 16 x 2 m, its corners on the true ones.
      ++corridors;
      EXPECT_NEAR(size.x(), 16.0, 0.002);
      EXPECT_NEAR(low.x() - kOffset.x(), 0.0, 0.002);
      EXPECT_NEAR(low.y() - kOffset.y(), 0.0, 0.002);
      continue;
    }
    // An office: four corners, 4.85 m deep (y 2.15 to 7), 5.2 or 5.3 m wide.
    EXPECT_NEAR(size.y(), 4.85, 0.002);
    EXPECT_TRUE(std::abs(size.x() - 5.2) < 0.002 || std::abs(size.x() - 5.3) < 0.002) << size.x();
  }
  EXPECT_EQ(corridors, 1u);
  if (const char* keep = std::getenv("PLUMB_TEST_IMAGES")) {
    std::ofstream(std::string(keep) + "/office-plan-2.4m.svg") << floorPlanSvg(plan);
    std::ofstream(std::string(keep) + "/office-plan-2.4m.dxf") << floorPlanDxf(plan);
  }
}

}  // namespace
}  // namespace plumb::cad
