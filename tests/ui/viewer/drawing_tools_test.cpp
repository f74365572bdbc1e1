// The drawing tools on the room corner of room_corner.h, driven as the viewer drives them: a
// pointer snapped at a pixel, then a click, a key or Enter. Each result is checked against the
// geometry it must have, and undo must take it back.

#include "ui/viewer/drawing_tools.h"

#include <gtest/gtest.h>

#include <algorithm>

#include "engine/ecs/history.h"
#include "tests/ui/viewer/room_corner.h"
#include "ui/viewer/components.h"
#include "ui/viewer/direction_finding.h"
#include "ui/viewer/scene_state.h"

namespace plumb::viewer {
namespace {

constexpr double kExact = 1e-9;

class DrawingToolsTest : public ::testing::Test {
 protected:
  void SetUp() override { room_ = fixtures::makeRoomCorner(scene_.registry()); }

  void use(Tool tool) {
    tools_.reset();
    scene_.registry().patch<ToolState>(scene_.toolEntity(), [&](ToolState& t) { t.active = tool; });
  }

  // The pointer over the pixel where `world` appears, snapped as the viewer snaps it; a click
  // over nothing finds `cloud_point` when one is given (the frame's pick).
  Pointer pointerAt(const Eigen::Vector3d& world, Eigen::Vector2d motion_px = Eigen::Vector2d::Zero(),
                    std::optional<Eigen::Vector3d> cloud_point = std::nullopt) {
    const Eigen::Vector2d pixel = room_.pixelOf(world);
    Pointer pointer;
    pointer.snap =
        snapCursor(scene_.registry(), room_.camera, pixel.x(), pixel.y(), [&](double, double) { return cloud_point; });
    pointer.ray = view::rayThroughPixel(room_.camera, pixel.x(), pixel.y());
    pointer.pixel = pixel;
    pointer.motion_px = motion_px;
    return pointer;
  }
  void clickAt(const Eigen::Vector3d& world) {
    const Pointer pointer = pointerAt(world);
    tools_.hover(pointer, room_.camera);
    tools_.click(pointer, room_.camera);
  }
  void hoverAt(const Eigen::Vector3d& world, Eigen::Vector2d motion_px = Eigen::Vector2d::Zero()) {
    tools_.hover(pointerAt(world, motion_px), room_.camera);
  }
  void typeAndEnter(const std::string& text, const Eigen::Vector3d& pointer_at) {
    for (const char c : text) tools_.type(c);
    tools_.enter(pointerAt(pointer_at), room_.camera);
  }

  std::vector<ecs::Entity> polygons() const {
    std::vector<ecs::Entity> found;
    scene_.registry().view<Polygon>().each([&](ecs::Entity e, const Polygon&) { found.push_back(e); });
    return found;
  }
  const Polygon& polygon(ecs::Entity entity) const { return scene_.registry().get<Polygon>(entity); }
  const DrawingState& drawing() const { return scene_.tool().drawing; }

  // A quadrilateral on the floor, drawn with snapped clicks: the corner, then three points of the
  // floor's plane, closed by clicking the first vertex again.
  ecs::Entity drawFloorSquare() {
    use(Tool::kPolygon);
    clickAt({0, 0, 0});  // the corner
    clickAt({1.2, 0.3, 0.0});
    clickAt({1.2, 1.2, 0.0});
    clickAt({0.3, 1.2, 0.0});
    clickAt({0, 0, 0});  // the first vertex: closes
    EXPECT_EQ(polygons().size(), 1u) << drawing().message;
    return polygons().empty() ? ecs::kNullEntity : polygons().front();
  }

  SceneState scene_;
  DrawingTools tools_{scene_};
  fixtures::RoomCorner room_;
};

TEST_F(DrawingToolsTest, APolygonSnappedToOneSegmentsFeaturesLiesOnItsPlane) {
  const ecs::Entity square = drawFloorSquare();
  ASSERT_NE(square, ecs::kNullEntity);
  const Polygon& p = polygon(square);
  EXPECT_EQ(p.plane, room_.segments[2]) << "every vertex snapped to the floor or its corner";
  ASSERT_EQ(p.vertices.size(), 4u);
  for (const Eigen::Vector3d& vertex : p.vertices) EXPECT_NEAR(vertex.z(), 0.0, kExact);
  EXPECT_NEAR(p.vertices[0].norm(), 0.0, kExact) << "the first vertex is the corner itself";
  EXPECT_NEAR((p.vertices[2] - Eigen::Vector3d(1.2, 1.2, 0)).norm(), 0.0, 1e-6);
  EXPECT_EQ(scene_.history().undoName(), "Polygon");
  scene_.history().undo();
  EXPECT_TRUE(polygons().empty());
}

TEST_F(DrawingToolsTest, ARectangleFromThreePointsHasRightAngles) {
  use(Tool::kPolygon);
  scene_.registry().patch<ToolState>(scene_.toolEntity(), [](ToolState& t) { t.drawing.rectangle = true; });
  // On the wall x = 0: one side along the floor, the third point anywhere on the opposite side.
  clickAt({0, 0.3, 0.1});
  clickAt({0, 1.5, 0.1});
  clickAt({0, 1.2, 1.2});
  ASSERT_EQ(polygons().size(), 1u) << drawing().message;
  const Polygon& p = polygon(polygons().front());
  ASSERT_EQ(p.vertices.size(), 4u);
  const Eigen::Vector3d side = p.vertices[1] - p.vertices[0], width = p.vertices[2] - p.vertices[1];
  EXPECT_NEAR(side.dot(width), 0.0, 1e-9);
  EXPECT_NEAR(width.norm(), 1.1, 1e-6) << "the opposite side passes through the third point";
  EXPECT_NEAR((p.vertices[3] - p.vertices[0] - width).norm(), 0.0, 1e-9);
  for (const Eigen::Vector3d& vertex : p.vertices) EXPECT_NEAR(vertex.x(), 0.0, 1e-9) << "on the wall";
}

TEST_F(DrawingToolsTest, AFreePolygonOffItsPlaneIsRefusedWithTheVertexNamed) {
  use(Tool::kPolygon);
  // Points of the cloud only (no features): three on the floor's level, the fourth 5 cm above.
  const auto click_point = [&](const Eigen::Vector3d& world) {
    const Pointer pointer = pointerAt(world, Eigen::Vector2d::Zero(), world);
    tools_.click(Pointer{Snap{Snap::Kind::kPoint, world, ecs::kNullEntity, 0.0}, pointer.ray, pointer.pixel, {}},
                 room_.camera);
  };
  click_point({3.0, 3.0, 0.0});
  click_point({3.5, 3.0, 0.0});
  click_point({3.5, 3.5, 0.05});
  click_point({3.0, 3.5, 0.0});
  tools_.enter(pointerAt({3, 3, 0}), room_.camera);
  EXPECT_TRUE(polygons().empty());
  EXPECT_NE(drawing().message.find("off the plane"), std::string::npos) << drawing().message;
}

TEST_F(DrawingToolsTest, APickedPolygonThatAnUndoTakesAwayIsForgotten) {
  drawFloorSquare();
  use(Tool::kMove);
  clickAt({0.5, 0.5, 0.0});
  clickAt({1.2, 1.2, 0.0});
  ASSERT_TRUE(drawing().base);
  scene_.history().undo();  // the polygon's creation
  ASSERT_TRUE(polygons().empty());
  hoverAt({1.5, 1.5, 0.0});  // the tool notices before it would move a polygon that is gone
  EXPECT_EQ(drawing().polygon, ecs::kNullEntity);
  EXPECT_FALSE(drawing().base);
  EXPECT_NE(drawing().message.find("gone"), std::string::npos) << drawing().message;
  clickAt({1.5, 1.5, 0.0});  // and a click asks for a polygon again
  EXPECT_EQ(drawing().message, "click a polygon");
}

TEST_F(DrawingToolsTest, BackspaceTakesAVertexAndItsPlaneBack) {
  use(Tool::kPolygon);
  clickAt({0, 0, 0});        // the corner: the walls and the floor
  clickAt({1.2, 0.3, 0.0});  // the floor: the polygon would go on it
  tools_.backspace();
  tools_.backspace();
  EXPECT_TRUE(drawing().vertices.empty());
  // A point of the cloud above the floor is now taken as it is, not where the ray meets the floor.
  const Eigen::Vector3d above(3.0, 3.0, 0.5);
  Pointer pointer = pointerAt(above);
  pointer.snap = Snap{Snap::Kind::kPoint, above, ecs::kNullEntity, 0.0};
  tools_.click(pointer, room_.camera);
  tools_.hover(pointer, room_.camera);
  ASSERT_EQ(drawing().vertices.size(), 1u);
  EXPECT_NEAR((drawing().vertices[0] - above).norm(), 0.0, 1e-12);
}

TEST_F(DrawingToolsTest, AtACornerTheDirectionFollowsThePointersMovement) {
  const Eigen::Vector3d corner = Eigen::Vector3d::Zero();
  const Snap snap{Snap::Kind::kCorner, corner, room_.corner, 0.0};
  // Moving the pointer along the image of the x axis picks the edge along x, signed with it.
  const Eigen::Vector2d along_x = room_.pixelOf({0.1, 0, 0}) - room_.pixelOf(corner);
  const std::optional<Direction> x = findDirection(scene_.registry(), room_.camera, snap, along_x.normalized() * 4.0);
  ASSERT_TRUE(x);
  EXPECT_NEAR(x->vector.x(), 1.0, 1e-9);
  const Eigen::Vector2d down_z = room_.pixelOf({0, 0, -0.1}) - room_.pixelOf(corner);
  const std::optional<Direction> z = findDirection(scene_.registry(), room_.camera, snap, down_z.normalized() * 4.0);
  ASSERT_TRUE(z);
  EXPECT_NEAR(z->vector.z(), -1.0, 1e-9);
  // On a plane: its normal, towards the eye.
  const std::optional<Direction> normal =
      findDirection(scene_.registry(), room_.camera, Snap{Snap::Kind::kPlane, {1, 1, 0}, room_.segments[2], 0.0}, {});
  ASSERT_TRUE(normal);
  EXPECT_NEAR(normal->vector.z(), 1.0, 1e-9);
}

TEST_F(DrawingToolsTest, AMoveAlongALockedDirectionEndsWhereTheLineMeetsTheSnappedPlane) {
  const ecs::Entity square = drawFloorSquare();
  // A second floor 0.75 m up, where the square must go.
  const ecs::Entity upper = fixtures::addSquareSegment(scene_.registry(), {0, 0, 0.75}, Eigen::Vector3d::UnitX(),
                                                       Eigen::Vector3d::UnitY(), 2.0);
  use(Tool::kMove);
  clickAt({0.5, 0.5, 0.0});  // picks the square
  ASSERT_EQ(drawing().polygon, square);
  clickAt({1.2, 1.2, 0.0});  // the base: the square's vertex
  ASSERT_TRUE(drawing().base);
  // Point at the floor to find its normal, lock it, then point at the upper floor anywhere.
  hoverAt({1.6, 1.7, 0.0});
  tools_.lockDirection(true);
  ASSERT_TRUE(drawing().direction_locked);
  const Pointer on_upper = pointerAt({1.7, 0.4, 0.75});
  ASSERT_TRUE(on_upper.snap && on_upper.snap->source == upper);
  tools_.hover(on_upper, room_.camera);
  tools_.click(on_upper, room_.camera);
  const Polygon& moved = polygon(square);
  EXPECT_NEAR((moved.vertices[2] - Eigen::Vector3d(1.2, 1.2, 0.75)).norm(), 0.0, 1e-9) << "straight up, not sideways";
  EXPECT_EQ(moved.plane, ecs::kNullEntity) << "off the floor now";
  EXPECT_EQ(scene_.history().undoName(), "Move polygon");
  scene_.history().undo();
  EXPECT_NEAR(polygon(square).vertices[2].z(), 0.0, kExact);
  EXPECT_EQ(polygon(square).plane, room_.segments[2]);
}

TEST_F(DrawingToolsTest, CopiesChainAndATypedDistanceRunsAlongTheDirection) {
  drawFloorSquare();
  use(Tool::kMove);
  scene_.registry().patch<ToolState>(scene_.toolEntity(), [](ToolState& t) { t.drawing.copy = true; });
  clickAt({0.5, 0.5, 0.0});
  clickAt({0, 0, 0});  // base: the corner (and the square's first vertex)
  // A typed distance runs towards the pointer: 0.4 m along the edge x = y = 0 (up the wall's edge).
  hoverAt({0, 0, 1.0});
  typeAndEnter("0.4", {0, 0, 1.0});
  ASSERT_EQ(polygons().size(), 2u) << drawing().message;
  // The copy is the next copy's origin: another 0.4 m up.
  hoverAt({0, 0, 1.5});
  typeAndEnter("0.4", {0, 0, 1.5});
  ASSERT_EQ(polygons().size(), 3u);
  double highest = 0.0;
  for (const ecs::Entity e : polygons()) highest = std::max(highest, polygon(e).vertices[0].z());
  EXPECT_NEAR(highest, 0.8, 1e-9);
  EXPECT_EQ(scene_.history().undoName(), "Copy polygon");
}

TEST_F(DrawingToolsTest, AfterACopySlashNSpreadsCopiesBetweenAndXNContinues) {
  drawFloorSquare();
  use(Tool::kMove);
  scene_.registry().patch<ToolState>(scene_.toolEntity(), [](ToolState& t) { t.drawing.copy = true; });
  clickAt({0.5, 0.5, 0.0});
  clickAt({0, 0, 0});
  hoverAt({0, 0, 1.0});
  typeAndEnter("1.2", {0, 0, 1.0});  // a copy 1.2 m up the wall's edge
  typeAndEnter("/4", {0, 0, 1.0});   // three more between: 0.3, 0.6, 0.9
  std::vector<double> heights;
  for (const ecs::Entity e : polygons()) heights.push_back(polygon(e).vertices[0].z());
  std::sort(heights.begin(), heights.end());
  ASSERT_EQ(heights.size(), 5u) << drawing().message;
  for (std::size_t i = 0; i < heights.size(); ++i) EXPECT_NEAR(heights[i], 0.3 * static_cast<double>(i), 1e-9);
  EXPECT_EQ(scene_.history().undoName(), "Copy polygon 3 times");
  scene_.history().undo();
  EXPECT_EQ(polygons().size(), 2u) << "one edit";
  // "x3": the copies go on at 1.2 m steps to three in all.
  typeAndEnter("x3", {0, 0, 1.0});
  heights.clear();
  for (const ecs::Entity e : polygons()) heights.push_back(polygon(e).vertices[0].z());
  std::sort(heights.begin(), heights.end());
  ASSERT_EQ(heights.size(), 4u);
  EXPECT_NEAR(heights.back(), 3.6, 1e-9);
  typeAndEnter("/1", {0, 0, 1.0});
  EXPECT_NE(drawing().message.find("/N"), std::string::npos) << "a count below 2 is refused";
}

TEST_F(DrawingToolsTest, AnExtrusionReachesTheSnappedPlaneOrATypedHeight) {
  const ecs::Entity square = drawFloorSquare();
  fixtures::addSquareSegment(scene_.registry(), {0, 0, 1.25}, Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY(), 2.0);
  use(Tool::kExtrude);
  clickAt({0.5, 0.5, 0.0});
  ASSERT_EQ(drawing().polygon, square);
  clickAt({1.6, 1.7, 1.25});  // the plane 1.25 m up
  EXPECT_NEAR((polygon(square).extrusion - Eigen::Vector3d(0, 0, 1.25)).norm(), 0.0, 1e-9) << drawing().message;
  EXPECT_EQ(scene_.history().undoName(), "Extrude");
  // Again, with a typed height.
  use(Tool::kExtrude);
  clickAt({0.5, 0.5, 0.0});
  typeAndEnter("0.3", {0.5, 0.5, 0.0});
  EXPECT_NEAR(std::abs(polygon(square).extrusion.z()), 0.3, 1e-9) << drawing().message;
  scene_.history().undo();
  EXPECT_NEAR(polygon(square).extrusion.z(), 1.25, 1e-9);
}

TEST_F(DrawingToolsTest, ACornerOfThreeSelectedSegmentsNeedsNoPoints) {
  ecs::Registry& registry = scene_.registry();
  // Three planes that meet at (2, 2, 2) where no segment reaches.
  const ecs::Entity a =
      fixtures::addSquareSegment(registry, {2, -5, -5}, Eigen::Vector3d::UnitY(), Eigen::Vector3d::UnitZ(), 1.0);
  const ecs::Entity b =
      fixtures::addSquareSegment(registry, {-5, 2, -5}, Eigen::Vector3d::UnitZ(), Eigen::Vector3d::UnitX(), 1.0);
  const ecs::Entity c =
      fixtures::addSquareSegment(registry, {-5, -5, 2}, Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY(), 1.0);
  scene_.select(a, false);
  scene_.select(b, true);
  auto refused = scene_.addCornerOfSelected();
  ASSERT_TRUE(std::holds_alternative<std::string>(refused));
  EXPECT_NE(std::get<std::string>(refused).find("2 selected"), std::string::npos);
  scene_.select(c, true);
  auto made = scene_.addCornerOfSelected();
  ASSERT_TRUE(std::holds_alternative<ecs::Entity>(made));
  const Corner& corner = registry.get<Corner>(std::get<ecs::Entity>(made));
  EXPECT_NEAR((corner.position - Eigen::Vector3d(2, 2, 2)).norm(), 0.0, 1e-9);
  EXPECT_TRUE(registry.has<SnapCandidate>(std::get<ecs::Entity>(made)));
  EXPECT_TRUE(std::holds_alternative<std::string>(scene_.addCornerOfSelected())) << "one corner per three";
  EXPECT_EQ(scene_.history().undoName(), "Corner");
}

TEST_F(DrawingToolsTest, RenameAndGroupsAreUndoable) {
  const ecs::Entity square = drawFloorSquare();
  scene_.select(square, false);
  scene_.select(room_.segments[2], true);
  const ecs::Entity group = scene_.groupSelected();
  ASSERT_NE(group, ecs::kNullEntity);
  EXPECT_EQ(scene_.registry().get<InGroup>(square).group, group);
  scene_.rename(group, "ground floor");
  scene_.rename(square, "slab");
  EXPECT_EQ(scene_.registry().get<Group>(group).name, "ground floor");
  EXPECT_EQ(polygon(square).name, "slab");
  scene_.history().undo();
  EXPECT_EQ(polygon(square).name, "Polygon 1");
  scene_.history().undo();
  scene_.history().undo();
  EXPECT_FALSE(scene_.registry().has<InGroup>(square));
  EXPECT_FALSE(scene_.registry().alive(group));
}

}  // namespace
}  // namespace plumb::viewer
