// The floor plan of grown walls on a simulated scan (issue 22, point 3): the room scene
// (docs/simulator.md: 7 x 5 x 2.5 m, a window recess in the y+ wall from x 2.5 to 4.3 m and
// z 0.9 to 2.1 m), scanned at 2 mm noise, a click on each of its four walls seen from 3 m, and the
// section through the clicked segments.

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

#include "cad/floor_plan.h"
#include "engine/lod/node_cache.h"
#include "engine/lod/octree_builder.h"
#include "reco/region_grower.h"
#include "reco/sim/simulation.h"
#include "engine/core/error.h"
#include "tests/support/temp_directory.h"

namespace plumb::cad {
namespace {

const Eigen::Vector3d kOffset(512000.0, 5403000.0, 250.0);

// A wall of a simulated scene: a click on it (scene frame) and its true plane, x or y = value.
struct TrueWall {
  Eigen::Vector3d click;
  int axis;  // 0: x = value, 1: y = value
  double value;
};

// `scene` simulated at 2 mm noise with `points`, imported, and a grow at each wall's click seen
// from 3 m: a project of the clicked segments, each once (a click on a surface a segment already
// holds adds nothing, as in the viewer), and for each segment the wall first clicked on it.
struct GrownWalls {
  Project project;
  std::vector<TrueWall> walls;  // walls[id - 1]: the true wall of segment id
};
GrownWalls grownWalls(const char* scene, std::uint64_t points, const std::vector<TrueWall>& walls) {
  const test::TempDirectory directory(std::string("plumb_FloorPlanOfGrownWalls_") + scene);
  reco::sim::SimulationRequest request;
  request.scene = scene;
  request.scanner.noise_m = 0.002;
  request.scanner.seed = 1;
  request.target_points = points;
  request.offset = kOffset;
  request.ply_path = directory.file("scan.ply");
  reco::sim::simulate(request);
  lod::BuildOptions build;
  build.sources = lod::fileSources({request.ply_path});
  build.output = directory.file("scan.plumb");
  lod::buildOctree(build);
  lod::NodeCache cache(lod::Octree::open(build.output), 256 << 20);
  GrownWalls grown;
  Project& project = grown.project;
  for (const TrueWall& wall : walls) {
    const Eigen::Vector3d seed = kOffset + wall.click;
    const reco::GrowSnapshot result = reco::growRegions(cache, reco::parametersForView(reco::viewFromDistance(seed, 3.0)));
    const reco::SegmentSnapshot* clicked = nullptr;
    for (const reco::SegmentSnapshot& segment : result.segments) {
      if (segment.plane.valid && segment.outline &&
          (clicked == nullptr || segment.plane.distance(seed) < clicked->plane.distance(seed))) {
        clicked = &segment;
      }
    }
    if (clicked == nullptr) throw Error("no segment grew at a click");
    bool held = false;
    for (const Segment& earlier : project.segments) {
      held = held || (std::abs(earlier.plane.normal.dot(clicked->plane.normal)) > std::cos(0.1 * M_PI / 180.0) &&
                      earlier.plane.distance(clicked->plane.centroid) < 0.005 &&
                      std::abs(static_cast<double>(earlier.plane.point_count) -
                               static_cast<double>(clicked->plane.point_count)) <
                          0.01 * static_cast<double>(earlier.plane.point_count));
    }
    if (held) continue;
    const ItemId id = project.segments.size() + 1;
    project.segments.push_back({id, "Wall " + std::to_string(id), kNoItem, clicked->plane, *clicked->outline});
    grown.walls.push_back(wall);
  }
  return grown;
}

// How far `p` lies from the true plane of `wall`.
double offWall(const TrueWall& wall, const Eigen::Vector3d& p) {
  return std::abs((p - kOffset)[wall.axis] - wall.value);
}

// Every line of the plan on its wall's true plane, within `tolerance`.
void expectLinesOnTheirWalls(const FloorPlan& plan, const std::vector<TrueWall>& walls, double tolerance) {
  for (const PlanLine& line : plan.lines) {
    const TrueWall& wall = walls.at(line.segment - 1);
    const Eigen::Vector3d a = line.start - kOffset, b = line.end - kOffset;
    std::printf("wall %llu: (%.3f, %.3f) to (%.3f, %.3f), ends %.3f and %.3f mm off its true plane\n",
                static_cast<unsigned long long>(line.segment), a.x(), a.y(), b.x(), b.y(), offWall(wall, line.start) * 1e3,
                offWall(wall, line.end) * 1e3);
    EXPECT_LT(offWall(wall, line.start), tolerance) << "wall " << line.segment;
    EXPECT_LT(offWall(wall, line.end), tolerance) << "wall " << line.segment;
  }
}

// The room (docs/simulator.md): its four walls.
const std::vector<TrueWall> kRoomWalls{{{0.0, 2.5, 1.2}, 0, 0.0},
                                       {{3.5, 0.0, 1.2}, 1, 0.0},
                                       {{7.0, 2.5, 1.2}, 0, 7.0},
                                       {{1.5, 5.0, 1.6}, 1, 5.0}};

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
  std::printf("window opening: %.3f m wide, from x %.3f to %.3f m\n", window->width_m,
              (window->start - kOffset).x(), (window->end - kOffset).x());
  constexpr double kSpacing = 0.056;
  EXPECT_LT(window->width_m, 1.8 + 0.005);
  EXPECT_GT(window->width_m, 1.8 - 2.0 * kSpacing);
  const double from = std::min((window->start - kOffset).x(), (window->end - kOffset).x());
  EXPECT_GT(from, 2.5 - 0.005);
  EXPECT_LT(from, 2.5 + kSpacing);

  // PLUMB_TEST_IMAGES=DIR keeps both plans' drawings there for a person to look at.
  if (const char* keep = std::getenv("PLUMB_TEST_IMAGES")) {
    std::ofstream(std::string(keep) + "/room-plan-2.3m.svg") << floorPlanSvg(plan);
    std::ofstream(std::string(keep) + "/room-plan-1.2m.svg") << floorPlanSvg(sill);
    std::ofstream(std::string(keep) + "/room-plan-1.2m.dxf") << floorPlanDxf(sill);
  }
}

// The office (docs/simulator.md): a 16 x 2 m corridor and three offices beside it, behind walls
// 0.15 m thick. Each room's four walls, clicked at 2.3 m, above the doors and windows.
std::vector<TrueWall> officeWalls() {
  std::vector<TrueWall> walls{{{0.0, 1.0, 2.3}, 0, 0.0},
                              {{16.0, 1.0, 2.3}, 0, 16.0},
                              {{8.0, 0.0, 2.3}, 1, 0.0},
                              {{8.0, 2.0, 2.3}, 1, 2.0}};
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
// thick within 2 mm, and every office closed. The offices' coplanar walls come out as one segment
// each side (the grower carries a face past a partition's end into the next office), which the
// plan cuts where it runs through a wall. The corridor stays open: its long walls, seen from its
// one station at grazing angles, grow only to 2.75 m from its ends at this detail, farther than
// the join gap; closing it takes grows near its ends (docs/floor-plans.md).
TEST(FloorPlanOfGrownWalls, EveryOfficeCloses) {
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
  EXPECT_EQ(closed, 3u) << "the three offices";
  // The corridor's wall and the offices' (one segment), and the two walls between offices.
  EXPECT_EQ(plan.walls.size(), 3u);
  for (const PlanChain& chain : plan.chains) {
    if (!chain.closed) continue;
    // An office: four corners, 4.85 m deep (y 2.15 to 7), 5.2 or 5.3 m wide.
    ASSERT_EQ(chain.vertices.size(), 4u);
    Eigen::Vector3d low = chain.vertices[0], high = chain.vertices[0];
    for (const Eigen::Vector3d& v : chain.vertices) {
      low = low.cwiseMin(v);
      high = high.cwiseMax(v);
    }
    EXPECT_NEAR((high - low).y(), 4.85, 0.002);
    EXPECT_TRUE(std::abs((high - low).x() - 5.2) < 0.002 || std::abs((high - low).x() - 5.3) < 0.002)
        << (high - low).x();
  }
  if (const char* keep = std::getenv("PLUMB_TEST_IMAGES")) {
    std::ofstream(std::string(keep) + "/office-plan-2.4m.svg") << floorPlanSvg(plan);
  }
}

}  // namespace
}  // namespace plumb::cad
