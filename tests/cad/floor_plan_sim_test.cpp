// The floor plan of grown walls on a simulated scan (issue 22, point 3): the room scene
// (docs/simulator.md: 7 x 5 x 2.5 m, a window recess in the y+ wall from x 2.5 to 4.3 m and
// z 0.9 to 2.1 m), scanned at 2 mm noise, a click on each of its four walls seen from 3 m, and the
// section through the clicked segments. The office's plan is floor_plan_office_test.cpp.

#include <gtest/gtest.h>

#include <Eigen/Core>
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

// The room (docs/simulator.md): its four walls.
const std::vector<TrueWall> kRoomWalls{
    {{0.0, 2.5, 1.2}, 0, 0.0}, {{3.5, 0.0, 1.2}, 1, 0.0}, {{7.0, 2.5, 1.2}, 0, 7.0}, {{1.5, 5.0, 1.6}, 1, 5.0}};

// Above the window and the door: the four walls make one closed outline whose corners are the
// room's, and every line lies on its true wall, within 2 mm.
TEST(FloorPlanOfGrownWalls, TheRoomClosesOnItsTrueCornersAndTheWindowIsAnOpening) {
  const GrownWalls grown = grownWalls("room", 200'000, kRoomWalls);
  const Project& project = grown.project;
  const FloorPlan plan = floorPlanAt(project, {.height_m = kOffset.z() + 2.3});
  EXPECT_EQ(plan.wall_faces, 4u);
  ASSERT_EQ(plan.lines.size(), 4u);
  EXPECT_EQ(plan.joins, 4u);
  expectLinesOnTheirWalls(plan, grown.walls, 0.002);
  ASSERT_EQ(plan.chains.size(), 1u);
  EXPECT_TRUE(plan.chains[0].closed);
  ASSERT_EQ(plan.chains[0].vertices.size(), 4u);
  for (const Eigen::Vector3d& corner : {Eigen::Vector3d(0, 0, 2.3), Eigen::Vector3d(7, 0, 2.3),
                                        Eigen::Vector3d(7, 5, 2.3), Eigen::Vector3d(0, 5, 2.3)}) {
    double nearest = INFINITY;
    for (const Eigen::Vector3d& v : plan.chains[0].vertices) nearest = std::min(nearest, (v - kOffset - corner).norm());
    std::printf("corner (%g, %g): %.3f mm off\n", corner.x(), corner.y(), nearest * 1e3);
    EXPECT_LT(nearest, 0.002);
  }

  // At 1.2 m the section passes through the window recess: the y+ wall has an opening of the
  // window's width, 1.8 m from x 2.5 m. Its ends come from the segment's outline, which stops at
  // the last points, up to a point spacing short of the edge: 5.6 cm at this detail (a 3 m
  // view). One test with the section above, so that the scan is simulated once (each test runs
  // in a process of its own).
  const FloorPlan sill = floorPlanAt(project, {.height_m = kOffset.z() + 1.2});
  const PlanOpening* window = nullptr;
  for (const PlanOpening& opening : sill.openings) {
    if (opening.segment == 4) window = &opening;
  }
  ASSERT_NE(window, nullptr) << sill.openings.size() << " openings";
  std::printf("window opening: %.3f m wide, from x %.3f to %.3f m\n", window->width_m, (window->start - kOffset).x(),
              (window->end - kOffset).x());
  constexpr double kSpacing = 0.056;
  EXPECT_LT(window->width_m, 1.8 + 0.005);
  EXPECT_GT(window->width_m, 1.8 - 2.0 * kSpacing);
  const double from = std::min((window->start - kOffset).x(), (window->end - kOffset).x());
  EXPECT_GT(from, 2.5 - 0.005);
  EXPECT_LT(from, 2.5 + kSpacing);
  // The 2 m cabinet hides 1.2 m of the y+ wall at this height, more than the join gap: the wall
  // reaches the corner (0, 5) across the empty gap and meets the x- wall there, so the outline is
  // whole but for the door and the window.
  const auto meetsAtCabinetCorner = [&](const FloorPlan& cut) {
    const Eigen::Vector3d corner = kOffset + Eigen::Vector3d(0.0, 5.0, 1.2);
    std::size_t ends = 0;
    for (const PlanLine& line : cut.lines) {
      ends += (line.start - corner).norm() < 0.002 || (line.end - corner).norm() < 0.002 ? 1u : 0u;
    }
    return ends == 2;
  };
  EXPECT_TRUE(meetsAtCabinetCorner(sill));
  EXPECT_EQ(sill.chains.size(), 2u) << "split by the door and the window only";
  EXPECT_FALSE(meetsAtCabinetCorner(floorPlanAt(project, {.height_m = kOffset.z() + 1.2, .join_reach_m = 0.0})))
      << "without the reach, the corner behind the cabinet stays open";

  // PLUMB_TEST_IMAGES=DIR keeps both plans' drawings there for a person to look at.
  if (const char* keep = std::getenv("PLUMB_TEST_IMAGES")) {
    std::ofstream(std::string(keep) + "/room-plan-2.3m.svg") << floorPlanSvg(plan);
    std::ofstream(std::string(keep) + "/room-plan-1.2m.svg") << floorPlanSvg(sill);
    std::ofstream(std::string(keep) + "/room-plan-1.2m.dxf") << floorPlanDxf(sill);
  }
}

}  // namespace
}  // namespace plumb::cad
