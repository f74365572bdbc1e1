// The Measure tool on the room corner of room_corner.h, clicked where the viewer would click: each
// kind of measurement from its clicks, its value against the geometry, refusals with their
// reason, undo, and the round trip through a project.

#include "ui/viewer/measure_tool.h"

#include <gtest/gtest.h>

#include "cad/measurement.h"
#include "engine/ecs/history.h"
#include "tests/ui/viewer/room_corner.h"
#include "ui/viewer/components.h"
#include "ui/viewer/project_bridge.h"
#include "ui/viewer/scene_state.h"

namespace plumb::viewer {
namespace {

using cad::MeasureKind;

class MeasureToolTest : public ::testing::Test {
 protected:
  void SetUp() override {
    room_ = fixtures::makeRoomCorner(scene_.registry());
    // A table top 0.8 m above the floor, and a square drawn on the floor.
    table_ = fixtures::addSquareSegment(scene_.registry(), {1.0, 1.0, 0.8}, Eigen::Vector3d::UnitX(),
                                        Eigen::Vector3d::UnitY(), 0.5);
    square_ = scene_.registry().create();
    scene_.registry().emplace(square_, Polygon{{{0.2, 1.2, 0}, {0.8, 1.2, 0}, {0.8, 1.8, 0}, {0.2, 1.8, 0}},
                                               room_.segments[2],
                                               "Polygon 1",
                                               Eigen::Vector3d::Zero()});
    scene_.registry().patch<ToolState>(scene_.toolEntity(), [](ToolState& t) { t.active = Tool::kMeasure; });
  }

  // A click where `world` appears; the frame's pick finds `cloud_point` there, if given.
  void clickAt(const Eigen::Vector3d& world, std::optional<Eigen::Vector3d> cloud_point = std::nullopt) {
    const Eigen::Vector2d pixel = room_.pixelOf(world);
    tool_.click(room_.camera, pixel.x(), pixel.y(), [&](double, double) { return cloud_point; });
  }

  std::vector<ecs::Entity> measurements() const {
    std::vector<ecs::Entity> found;
    scene_.registry().view<Measurement>().each([&](ecs::Entity e, const Measurement&) { found.push_back(e); });
    return found;
  }
  const Measurement& last() const { return scene_.registry().get<Measurement>(measurements().back()); }
  cad::MeasureValue valueOf(const Measurement& m) const { return cad::measure(m.kind, m.terms); }
  const std::string& message() const { return scene_.tool().measure_message; }

  SceneState scene_;
  MeasureTool tool_{scene_};
  fixtures::RoomCorner room_;
  ecs::Entity table_, square_;
};

TEST_F(MeasureToolTest, ADistanceFromTheCornerToAPointOfTheFloor) {
  tool_.setKind(MeasureKind::kDistance);
  EXPECT_EQ(MeasureTool::prompt(scene_.tool()), "Click the first point");
  clickAt({0, 0, 0});
  EXPECT_EQ(MeasureTool::prompt(scene_.tool()), "Click the second point");
  clickAt({1.5, 0.5, 0});
  ASSERT_EQ(measurements().size(), 1u) << message();
  const Measurement& m = last();
  EXPECT_EQ(m.name, "Distance 1");
  EXPECT_NEAR(valueOf(m).value, std::hypot(1.5, 0.5), 1e-6);
  EXPECT_EQ(m.sources, (std::vector<ecs::Entity>{room_.corner, room_.segments[2]})) << "the corner, then the floor";
  EXPECT_EQ(message(), "Distance 1: " + cad::measureText(m.kind, valueOf(m)));
  EXPECT_TRUE(scene_.tool().measure_terms.empty()) << "the next click starts a new distance";
  EXPECT_EQ(scene_.history().undoName(), "Measure");
  scene_.history().undo();
  EXPECT_TRUE(measurements().empty());
}

TEST_F(MeasureToolTest, AnAngleBetweenAnEdgeAndAPlaneOrTwoPlanes) {
  tool_.setKind(MeasureKind::kAngle);
  clickAt({0, 0, 1.0});  // the walls' edge, not the corner nor the walls
  ASSERT_EQ(scene_.tool().measure_terms.size(), 1u) << message();
  EXPECT_EQ(scene_.tool().measure_terms[0].kind, cad::MeasureTerm::Kind::kLine);
  clickAt({1.5, 0.5, 0});  // the floor
  ASSERT_EQ(measurements().size(), 1u) << message();
  EXPECT_NEAR(valueOf(last()).value, 90.0, 1e-9);
  EXPECT_EQ(last().sources, (std::vector<ecs::Entity>{room_.edge, room_.segments[2]}));
  clickAt({0, 1.2, 1.2});  // wall x
  clickAt({1.2, 0, 1.2});  // wall y
  ASSERT_EQ(measurements().size(), 2u) << message();
  EXPECT_NEAR(valueOf(last()).value, 90.0, 1e-9);
  EXPECT_EQ(last().name, "Angle 2");
}

TEST_F(MeasureToolTest, HeightsAboveOneFloorUntilEscape) {
  tool_.setKind(MeasureKind::kHeight);
  clickAt({0, 1.0, 1.5});  // a wall is no floor
  EXPECT_TRUE(scene_.tool().measure_terms.empty());
  EXPECT_NE(message().find("not a floor: the floor is tilted 90.00"), std::string::npos) << message();
  clickAt({1.5, 0.5, 0});  // the floor
  EXPECT_EQ(MeasureTool::prompt(scene_.tool()), "Click a point: its height above the floor (Escape: another floor)");
  clickAt({0, 1.0, 1.5});   // a point of wall x
  clickAt({1.0, 0, 0.75});  // a point of wall y
  ASSERT_EQ(measurements().size(), 2u) << message();
  const std::vector<ecs::Entity> taken = measurements();
  EXPECT_NEAR(valueOf(scene_.registry().get<Measurement>(taken[0])).value, 1.5, 1e-6);
  EXPECT_NEAR(valueOf(scene_.registry().get<Measurement>(taken[1])).value, 0.75, 1e-6);
  EXPECT_EQ(scene_.tool().measure_terms.size(), 1u) << "the floor stays for the next point";
  // The floor deleted (an undo, a Delete): the next click starts over, with no floor.
  scene_.select(room_.segments[2], false);
  scene_.deleteSelected();
  clickAt({0, 1.0, 1.0});  // wall x: not a floor
  EXPECT_TRUE(scene_.tool().measure_terms.empty());
  EXPECT_EQ(measurements().size(), 2u);
  tool_.escape();
  EXPECT_TRUE(scene_.tool().measure_terms.empty());
  EXPECT_EQ(MeasureTool::prompt(scene_.tool()), "Click the floor");
}

TEST_F(MeasureToolTest, BetweenPlanesRefusesPlanesFarFromParallel) {
  tool_.setKind(MeasureKind::kBetweenPlanes);
  clickAt({0.5, 1.7, 0});  // the floor
  clickAt({1.2, 0, 1.2});  // wall y: perpendicular
  EXPECT_TRUE(measurements().empty());
  EXPECT_NE(message().find("not measured: the planes are 90.00"), std::string::npos) << message();
  EXPECT_EQ(scene_.tool().measure_terms.size(), 1u) << "the floor stays: another second plane may follow";
  clickAt({0.3, 1.2, 0});  // the floor again
  EXPECT_TRUE(measurements().empty());
  EXPECT_EQ(message(), "the same plane twice: click another");
  clickAt({1.3, 1.3, 0.8});  // the table top
  ASSERT_EQ(measurements().size(), 1u) << message();
  EXPECT_NEAR(valueOf(last()).value, 0.8, 1e-9);
  EXPECT_EQ(last().sources, (std::vector<ecs::Entity>{room_.segments[2], table_}));
}

TEST_F(MeasureToolTest, TheAreaOfADrawnPolygon) {
  tool_.setKind(MeasureKind::kArea);
  clickAt({1.5, 0.5, 0});  // the floor, no polygon
  EXPECT_TRUE(measurements().empty());
  EXPECT_EQ(message(), "no polygon there: draw one with the Polygon tool");
  clickAt({0.5, 1.5, 0});
  ASSERT_EQ(measurements().size(), 1u) << message();
  EXPECT_NEAR(valueOf(last()).value, 0.36, 1e-9);
  EXPECT_NEAR(*valueOf(last()).second, 2.4, 1e-9);
  EXPECT_EQ(last().sources, std::vector<ecs::Entity>{square_});
}

TEST_F(MeasureToolTest, APointToAPlaneFromAPointOfTheCloud) {
  tool_.setKind(MeasureKind::kPointToPlane);
  clickAt({0, 1.0, 1.0});  // wall x
  // The point of the cloud the frame's pick gives where no feature is: outside the room's corner.
  const Eigen::Vector3d beyond(3.0, -1.0, 0.3);
  const Eigen::Vector2d pixel = room_.pixelOf(beyond);
  tool_.click(room_.camera, pixel.x(), pixel.y(), [&](double, double) { return std::optional(beyond); });
  ASSERT_EQ(measurements().size(), 1u) << message();
  EXPECT_NEAR(valueOf(last()).value, 3.0, 1e-9);
  EXPECT_EQ(last().sources[1], ecs::kNullEntity) << "a point of the cloud is no item";
}

TEST_F(MeasureToolTest, MeasurementsGoThroughAProjectAndTheirNumberingContinues) {
  tool_.setKind(MeasureKind::kBetweenPlanes);
  clickAt({0.5, 1.7, 0});
  clickAt({1.3, 1.3, 0.8});
  tool_.setKind(MeasureKind::kArea);
  clickAt({0.5, 1.5, 0});
  ASSERT_EQ(measurements().size(), 2u) << message();
  const cad::Project project = projectOf(scene_.registry(), "cloud.plumb", std::nullopt);
  ASSERT_EQ(project.measurements.size(), 2u);
  const cad::Measurement& width = project.measurements[0];
  EXPECT_EQ(width.name, "Between planes 1");
  ASSERT_EQ(width.sources.size(), 2u);
  // The sources are the project's ids of the floor and the table.
  for (const cad::ItemId source : width.sources) {
    EXPECT_TRUE(std::any_of(project.segments.begin(), project.segments.end(),
                            [&](const cad::Segment& s) { return s.id == source; }));
  }
  EXPECT_EQ(project.measurements[1].sources[0], project.polygons[0].id);

  SceneState reopened;
  loadProject(project, reopened);
  std::vector<const Measurement*> loaded;
  reopened.registry().view<Measurement>().each([&](ecs::Entity, const Measurement& m) { loaded.push_back(&m); });
  ASSERT_EQ(loaded.size(), 2u);
  EXPECT_EQ(loaded[1]->name, "Area 2");
  EXPECT_NEAR(cad::measure(loaded[0]->kind, loaded[0]->terms).value, 0.8, 1e-9);
  EXPECT_TRUE(reopened.registry().has<Segment>(loaded[0]->sources[1]));
  const cad::MeasureTerm origin{cad::MeasureTerm::Kind::kPoint, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(), {}};
  const ecs::Entity next =
      reopened.addMeasurement(MeasureKind::kDistance, {origin, origin}, {ecs::kNullEntity, ecs::kNullEntity});
  EXPECT_EQ(reopened.registry().get<Measurement>(next).name, "Distance 3") << "numbered after the project's";
}

}  // namespace
}  // namespace plumb::viewer
