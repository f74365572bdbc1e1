#include "cad/floor_plan.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cstdlib>
#include <fstream>
#include <nlohmann/json.hpp>
#include <optional>

#include "tests/support/temp_directory.h"

namespace plumb::cad {
namespace {

// Survey coordinates, so that precision problems show.
const Eigen::Vector3d kOffset(512000.0, 5403000.0, 250.0);
constexpr double kHeight = 1.2;  // the section, above the floor at kOffset.z()

// A vertical wall face through the floor points `from` and `to` (scene frame), whose outline in
// its plane's coordinates (u from `from` towards `to`, v up from the floor) is `rings`.
Segment wallFace(ItemId id, const Eigen::Vector3d& from, const Eigen::Vector3d& to,
                 std::vector<std::vector<Eigen::Vector2d>> rings) {
  Segment segment;
  segment.id = id;
  segment.name = "Wall " + std::to_string(id);
  const Eigen::Vector3d along = (to - from).normalized();
  segment.plane.valid = true;
  segment.plane.normal = along.cross(Eigen::Vector3d::UnitZ());
  segment.plane.tangent = along;
  segment.plane.bitangent = Eigen::Vector3d::UnitZ();
  segment.plane.centroid = kOffset + 0.5 * (from + to) + Eigen::Vector3d(0, 0, 1.25);
  segment.plane.offset = -segment.plane.normal.dot(segment.plane.centroid);
  segment.outline.origin = kOffset + from;
  segment.outline.axis_u = along;
  segment.outline.axis_v = Eigen::Vector3d::UnitZ();
  segment.outline.shape.rings = std::move(rings);
  return segment;
}

// A rectangle from u0 to u1 and v0 to v1, counter-clockwise.
std::vector<Eigen::Vector2d> rectangle(double u0, double u1, double v0, double v1) {
  return {{u0, v0}, {u1, v0}, {u1, v1}, {u0, v1}};
}

// A 4 x 3 m room whose four walls' points stop `short_m` before each corner, as a scan's do.
Project room(double short_m) {
  const std::array<Eigen::Vector3d, 4> corners{Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(4, 0, 0),
                                               Eigen::Vector3d(4, 3, 0), Eigen::Vector3d(0, 3, 0)};
  Project project;
  for (std::size_t i = 0; i < 4; ++i) {
    const Eigen::Vector3d& from = corners[i];
    const Eigen::Vector3d& to = corners[(i + 1) % 4];
    const double length = (to - from).norm();
    project.segments.push_back(wallFace(i + 1, from, to, {rectangle(short_m, length - short_m, 0.05, 2.45)}));
  }
  return project;
}

TEST(FloorPlan, ARoomsWallsCloseAtTheirPlanesCornersWherePointsStopShort) {
  const FloorPlan plan = floorPlanAt(room(0.12), {.height_m = kOffset.z() + kHeight});
  EXPECT_EQ(plan.wall_faces, 4u);
  EXPECT_EQ(plan.lines.size(), 4u);
  EXPECT_EQ(plan.joins, 4u);
  EXPECT_TRUE(plan.openings.empty());
  ASSERT_EQ(plan.chains.size(), 1u);
  const PlanChain& chain = plan.chains[0];
  EXPECT_TRUE(chain.closed);
  ASSERT_EQ(chain.vertices.size(), 4u);
  for (const Eigen::Vector3d& corner :
       {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(4, 0, 0), Eigen::Vector3d(4, 3, 0), Eigen::Vector3d(0, 3, 0)}) {
    const Eigen::Vector3d want = kOffset + corner + Eigen::Vector3d(0, 0, kHeight);
    double nearest = 1e9;
    for (const Eigen::Vector3d& v : chain.vertices) nearest = std::min(nearest, (v - want).norm());
    EXPECT_LT(nearest, 1e-9) << "corner " << corner.transpose();
  }
}

TEST(FloorPlan, EndsFartherThanTheJoinGapStayOpen) {
  const FloorPlan plan = floorPlanAt(room(0.4), {.height_m = kOffset.z() + kHeight, .join_gap_m = 0.3});
  EXPECT_EQ(plan.joins, 0u);
  EXPECT_EQ(plan.chains.size(), 4u);
  for (const PlanChain& chain : plan.chains) EXPECT_FALSE(chain.closed);
}

// A corridor 8 x 2 m whose long walls stop 2.5 m short of its ends (seen at grazing angles): they
// reach its end walls across the empty gaps, unless a face lies across a gap or the reach is off.
TEST(FloorPlan, AWallStoppedFarShortOfACornerReachesItAcrossAnEmptyGap) {
  const auto corridor = [](bool partition_across) {
    Project project;
    project.segments.push_back(wallFace(1, {0, 0, 0}, {8, 0, 0}, {rectangle(2.5, 5.5, 0.05, 2.45)}));
    project.segments.push_back(wallFace(2, {8, 0, 0}, {8, 2, 0}, {rectangle(0.1, 1.9, 0.05, 2.45)}));
    project.segments.push_back(wallFace(3, {8, 2, 0}, {0, 2, 0}, {rectangle(2.5, 5.5, 0.05, 2.45)}));
    project.segments.push_back(wallFace(4, {0, 2, 0}, {0, 0, 0}, {rectangle(0.1, 1.9, 0.05, 2.45)}));
    // A short partition standing across the gap of wall 1 at x = 1 m.
    if (partition_across) project.segments.push_back(wallFace(5, {1, -0.5, 0}, {1, 0.5, 0}, {rectangle(0, 1, 0, 2)}));
    return project;
  };
  const FloorPlan plan = floorPlanAt(corridor(false), {.height_m = kOffset.z() + kHeight});
  EXPECT_EQ(plan.joins, 4u);
  ASSERT_EQ(plan.chains.size(), 1u);
  EXPECT_TRUE(plan.chains[0].closed);
  for (const Eigen::Vector3d& v : plan.chains[0].vertices) {
    const Eigen::Vector3d local = v - kOffset;
    EXPECT_TRUE((std::abs(local.x()) < 1e-9 || std::abs(local.x() - 8) < 1e-9) &&
                (std::abs(local.y()) < 1e-9 || std::abs(local.y() - 2) < 1e-9))
        << "a corner off the corridor's: " << local.transpose();
  }
  // A face across the gap (x = 1): wall 1 does not reach past it to the x = 0 end, nor is the
  // partition, which it crosses in its middle, taken for a corner and cut.
  const FloorPlan blocked = floorPlanAt(corridor(true), {.height_m = kOffset.z() + kHeight});
  std::size_t closed = 0;
  for (const PlanChain& chain : blocked.chains) closed += chain.closed ? 1u : 0u;
  EXPECT_EQ(closed, 0u);
  for (const PlanLine& line : blocked.lines) {
    if (line.segment == 5) {
      EXPECT_NEAR((line.end - line.start).norm(), 1.0, 1e-9) << "the partition whole";
    }
    if (line.segment == 1) {
      EXPECT_GT(std::min(line.start.x(), line.end.x()) - kOffset.x(), 2.0) << "wall 1 stays";
    }
  }
  // No reach beyond the join gap: four open lines.
  const FloorPlan near = floorPlanAt(corridor(false), {.height_m = kOffset.z() + kHeight, .join_reach_m = 0.0});
  EXPECT_EQ(near.joins, 0u);
  EXPECT_EQ(near.chains.size(), 4u);
}

// A wall with a door 0.9 m wide and 2 m high: cut at 1.2 m it has an opening, at 2.2 m none.
TEST(FloorPlan, ADoorCutBySectionIsAnOpening) {
  Project project;
  project.segments.push_back(
      wallFace(1, {0, 0, 0}, {4, 0, 0}, {{{0, 0}, {1, 0}, {1, 2}, {1.9, 2}, {1.9, 0}, {4, 0}, {4, 2.5}, {0, 2.5}}}));
  const FloorPlan low = floorPlanAt(project, {.height_m = kOffset.z() + kHeight});
  ASSERT_EQ(low.lines.size(), 2u);
  ASSERT_EQ(low.openings.size(), 1u);
  EXPECT_NEAR(low.openings[0].width_m, 0.9, 1e-9);
  EXPECT_EQ(low.openings[0].segment, 1u);
  const FloorPlan high = floorPlanAt(project, {.height_m = kOffset.z() + 2.2});
  EXPECT_EQ(high.lines.size(), 1u);
  EXPECT_TRUE(high.openings.empty());
  // A gap narrower than an opening (a scan shadow) is closed.
  const FloorPlan closed = floorPlanAt(project, {.height_m = kOffset.z() + kHeight, .min_opening_m = 1.0});
  EXPECT_EQ(closed.lines.size(), 1u);
  EXPECT_TRUE(closed.openings.empty());
}

TEST(FloorPlan, TwoParallelFacesAWallApartAreOneWallOfTheirThickness) {
  Project project;
  project.segments.push_back(wallFace(1, {0, 0, 0}, {4, 0, 0}, {rectangle(0, 4, 0, 2.5)}));
  project.segments.push_back(wallFace(2, {4, 0.24, 0}, {0, 0.24, 0}, {rectangle(0.5, 4, 0, 2.5)}));
  project.segments.push_back(wallFace(3, {0, 2.0, 0}, {4, 2.0, 0}, {rectangle(0, 4, 0, 2.5)}));  // too far
  const FloorPlan plan = floorPlanAt(project, {.height_m = kOffset.z() + kHeight});
  ASSERT_EQ(plan.walls.size(), 1u);
  EXPECT_EQ(plan.walls[0].face_a, 1u);
  EXPECT_EQ(plan.walls[0].face_b, 2u);
  EXPECT_NEAR(plan.walls[0].thickness_m, 0.24, 1e-9);
}

// An inner wall that stops 10 cm short of an outer wall's middle ends on the outer wall's line.
TEST(FloorPlan, AnInnerWallMeetsAnOuterWallsMiddle) {
  Project project;
  project.segments.push_back(wallFace(1, {0, 0, 0}, {6, 0, 0}, {rectangle(0, 6, 0, 2.5)}));
  project.segments.push_back(wallFace(2, {3, 0, 0}, {3, 3, 0}, {rectangle(0.1, 3, 0, 2.5)}));
  const FloorPlan plan = floorPlanAt(project, {.height_m = kOffset.z() + kHeight});
  ASSERT_EQ(plan.lines.size(), 2u);
  const PlanLine& inner = plan.lines[1];
  const Eigen::Vector3d meeting = kOffset + Eigen::Vector3d(3, 0, kHeight);
  EXPECT_LT(std::min((inner.start - meeting).norm(), (inner.end - meeting).norm()), 1e-9);
  EXPECT_EQ(plan.joins, 0u) << "a T, not a corner";
  EXPECT_NEAR((plan.lines[0].end - plan.lines[0].start).norm(), 6.0, 1e-9) << "the outer wall unchanged";
}

// Two rooms side by side behind a partition 0.15 m thick, their back walls coplanar and grown as
// one face across the partition's end: the plan cuts that face where it runs through the
// partition, and each room closes on its own.
TEST(FloorPlan, AFaceCarriedPastAPartitionIsCutWhereItRunsThroughIt) {
  Project project;
  project.segments.push_back(wallFace(1, {0, 0, 0}, {8.15, 0, 0}, {rectangle(0, 8.15, 0, 2.5)}));  // front, both
  project.segments.push_back(wallFace(2, {8.15, 3, 0}, {0, 3, 0}, {rectangle(0, 8.15, 0, 2.5)}));  // back, both
  project.segments.push_back(wallFace(3, {0, 3, 0}, {0, 0, 0}, {rectangle(0, 3, 0, 2.5)}));
  project.segments.push_back(wallFace(4, {4, 0, 0}, {4, 3, 0}, {rectangle(0.05, 2.95, 0, 2.5)}));  // partition
  project.segments.push_back(wallFace(5, {4.15, 3, 0}, {4.15, 0, 0}, {rectangle(0.05, 2.95, 0, 2.5)}));
  project.segments.push_back(wallFace(6, {8.15, 0, 0}, {8.15, 3, 0}, {rectangle(0, 3, 0, 2.5)}));
  const FloorPlan plan = floorPlanAt(project, {.height_m = kOffset.z() + kHeight});
  ASSERT_EQ(plan.walls.size(), 1u);
  EXPECT_NEAR(plan.walls[0].thickness_m, 0.15, 1e-9);
  std::size_t closed = 0;
  for (const PlanChain& chain : plan.chains) closed += chain.closed ? 1u : 0u;
  EXPECT_EQ(closed, 2u);
  EXPECT_EQ(plan.lines.size(), 8u) << "the front and back faces in two each";
}

TEST(FloorPlan, FloorsTiltedPlanesAndSegmentsWithoutOutlineAreNotWalls) {
  Project project = room(0.0);
  Segment floor;
  floor.id = 10;
  floor.plane.valid = true;
  floor.plane.normal = Eigen::Vector3d::UnitZ();
  floor.plane.centroid = kOffset;
  floor.outline.shape.rings = {rectangle(0, 4, 0, 3)};
  project.segments.push_back(floor);
  Segment ramp = wallFace(11, {0, 1, 0}, {4, 1, 0}, {rectangle(0, 4, 0, 2.5)});
  ramp.plane.normal = Eigen::Vector3d(0, std::cos(0.2), std::sin(0.2));  // 11.5 degrees off vertical
  project.segments.push_back(ramp);
  Segment bare = wallFace(12, {0, 2, 0}, {4, 2, 0}, {});
  project.segments.push_back(bare);
  const FloorPlan plan = floorPlanAt(project, {.height_m = kOffset.z() + kHeight});
  EXPECT_EQ(plan.wall_faces, 4u);
  for (const PlanLine& line : plan.lines) EXPECT_LE(line.segment, 4u);
  // Above the walls' outlines there is nothing to cut.
  EXPECT_TRUE(floorPlanAt(project, {.height_m = kOffset.z() + 3.0}).lines.empty());
}

// The DXF read back by ezdxf (tests/cad/read_dxf.py), whose audit passes: the room's closed
// polyline at the section's height, the opening on its own layer.
TEST(FloorPlan, TheDxfReadsBackInEzdxfAndTheSvgIsToScale) {
  Project project = room(0.12);
  project.segments[0].outline.shape.rings = {
      {{0.12, 0.05}, {1.0, 0.05}, {1.0, 2.0}, {1.9, 2.0}, {1.9, 0.05}, {3.88, 0.05}, {3.88, 2.45}, {0.12, 2.45}}};
  const FloorPlan plan = floorPlanAt(project, {.height_m = kOffset.z() + kHeight});
  ASSERT_EQ(plan.openings.size(), 1u);
  test::TempDirectory dir;
  const std::string dxf_path = dir.file("plan.dxf");
  std::ofstream(dxf_path) << floorPlanDxf(plan);
  std::optional<std::string> python;
  for (const char* candidate : {"python3", "/usr/bin/python3"}) {
    if (std::system((std::string(candidate) + " -c 'import ezdxf' >/dev/null 2>&1").c_str()) == 0) {
      python = candidate;
      break;
    }
  }
  if (python) {
    const std::string out = dir.file("dxf.json");
    ASSERT_EQ(
        std::system((*python + " " + PLUMB_SOURCE_DIR + "/tests/cad/read_dxf.py " + dxf_path + " >" + out).c_str()), 0);
    const nlohmann::json dxf = nlohmann::json::parse(test::readFile(out));
    EXPECT_TRUE(dxf["audit_errors"].empty()) << dxf["audit_errors"].dump(1);
    std::size_t closed = 0, openings = 0;
    for (const nlohmann::json& polyline : dxf["polylines"]) {
      if (polyline["layer"] == "PLAN_OPENINGS") ++openings;
      if (polyline["layer"] == "PLAN_WALLS" && polyline["closed"].get<bool>()) ++closed;
      for (const nlohmann::json& vertex : polyline["wcs"]) {
        EXPECT_NEAR(vertex[2].get<double>(), kOffset.z() + kHeight, 1e-6);
      }
    }
    EXPECT_EQ(openings, 1u);
    EXPECT_EQ(closed, 0u) << "the door opens the room's loop";
  } else {
    std::printf("python3-ezdxf is not installed: the DXF is not read back\n");
  }
  const std::string svg = floorPlanSvg(plan);
  // 4 x 3 m plus a 0.5 m margin on each side, in millimetres.
  EXPECT_NE(svg.find("width=\"5000.000mm\" height=\"4000.000mm\""), std::string::npos) << svg;
  EXPECT_NE(svg.find("z = 251.200 m"), std::string::npos);
  EXPECT_NE(svg.find("stroke-dasharray"), std::string::npos);
}

}  // namespace
}  // namespace plumb::cad
