// Cursor snapping: corners before edges before planes before points, within a pixel radius;
// a corner with no point near it (a scan shadow) still snaps.

#include "ui/viewer/snapping.h"

#include <gtest/gtest.h>

#include "engine/ecs/registry.h"
#include "engine/view/camera_controls.h"
#include "tests/ui/viewer/room_corner.h"
#include "ui/viewer/components.h"

namespace plumb::viewer {
namespace {

// The room corner of room_corner.h.
class SnappingTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const fixtures::RoomCorner room = fixtures::makeRoomCorner(registry_);
    camera_ = room.camera;
    segments_ = room.segments;
    edge_ = room.edge;
    corner_ = room.corner;
  }

  Eigen::Vector2d pixelOf(const Eigen::Vector3d& world) const { return *view::pixelOf(camera_, world); }

  view::Camera camera_;
  ecs::Registry registry_;
  std::array<ecs::Entity, 3> segments_{};
  ecs::Entity edge_, corner_;
  const PointPicker no_points_ = [](double, double) { return std::optional<Eigen::Vector3d>{}; };
};

TEST_F(SnappingTest, ACornerWinsWithinTheRadiusEvenWithoutPoints) {
  const Eigen::Vector2d at = pixelOf({0, 0, 0}) + Eigen::Vector2d(5, -4);
  const std::optional<Snap> snap = snapCursor(registry_, camera_, at.x(), at.y(), no_points_);
  ASSERT_TRUE(snap);
  EXPECT_EQ(snap->kind, Snap::Kind::kCorner);
  EXPECT_EQ(snap->source, corner_);
  EXPECT_NEAR(snap->position.norm(), 0.0, 1e-12);
  EXPECT_NEAR(snap->distance_px, std::hypot(5.0, 4.0), 1e-6);
}

TEST_F(SnappingTest, NearAnEdgeTheSnapLiesOnItsLine) {
  const Eigen::Vector3d on_edge(0, 0, 1.2);
  const Eigen::Vector2d at = pixelOf(on_edge) + Eigen::Vector2d(6, 0);
  const std::optional<Snap> snap = snapCursor(registry_, camera_, at.x(), at.y(), no_points_);
  ASSERT_TRUE(snap);
  EXPECT_EQ(snap->kind, Snap::Kind::kEdge);
  EXPECT_EQ(snap->source, edge_);
  EXPECT_NEAR(snap->position.x(), 0.0, 1e-9);
  EXPECT_NEAR(snap->position.y(), 0.0, 1e-9);
  EXPECT_NEAR(snap->position.z(), 1.2, 0.02) << "where the cursor's ray passes nearest";
  // Beyond the support range's end (z = 1.8) the edge does not reach: the wall's plane does.
  const Eigen::Vector2d past = pixelOf({0, 0, 1.95}) + Eigen::Vector2d(0, 0);
  const std::optional<Snap> beyond = snapCursor(registry_, camera_, past.x(), past.y() - 14.0, no_points_);
  EXPECT_TRUE(!beyond || beyond->kind != Snap::Kind::kEdge);
}

TEST_F(SnappingTest, InsideAnOutlineTheSnapLiesOnThePlane) {
  const Eigen::Vector3d on_floor(1.2, 1.5, 0.0);
  const Eigen::Vector2d at = pixelOf(on_floor);
  const std::optional<Snap> snap = snapCursor(registry_, camera_, at.x(), at.y(), no_points_);
  ASSERT_TRUE(snap);
  EXPECT_EQ(snap->kind, Snap::Kind::kPlane);
  EXPECT_EQ(snap->source, segments_[2]);
  EXPECT_NEAR((snap->position - on_floor).norm(), 0.0, 1e-6);
}

// From straight above (a plan view, orthographic) the walls are edge on: no ray meets them, and a
// click beside a wall's line takes the wall, at the point of its outline nearest the cursor.
TEST_F(SnappingTest, AWallSeenEdgeOnSnapsNearItsLine) {
  camera_.projection = view::Projection::kOrthographic;
  camera_.position = {1.0, 1.0, 20.0};
  camera_.target = {1.0, 1.0, 0.0};
  camera_.up = Eigen::Vector3d::UnitY();
  camera_.ortho_height_m = 4.0;
  // Beside the wall x = 0 (segment 0), 6 pixels into the room, at y = 1.3 m; corners and edges
  // off, as a plane-only measurement asks.
  const Eigen::Vector2d at = pixelOf({0.0, 1.3, 2.0}) + Eigen::Vector2d(6, 0);
  SnapOptions planes_only;
  planes_only.corners = planes_only.edges = false;
  planes_only.edge_on_planes = true;
  const std::optional<Snap> snap = snapCursor(registry_, camera_, at.x(), at.y(), no_points_, planes_only);
  ASSERT_TRUE(snap);
  EXPECT_EQ(snap->kind, Snap::Kind::kPlane);
  EXPECT_EQ(snap->source, segments_[0]);
  EXPECT_NEAR(snap->position.x(), 0.0, 1e-9) << "on the wall's plane";
  EXPECT_NEAR(snap->position.y(), 1.3, 1e-6);
  EXPECT_NEAR(snap->position.z(), 2.0, 1e-9) << "on the wall's top edge, the nearer to the view, not its bottom";
  EXPECT_NEAR(snap->distance_px, 6.0, 1e-6);
  // A point snap (a drawing tool, a distance) does not take the edge-on wall: its height there
  // would be the outline's edge's. The floor under the cursor instead.
  planes_only.edge_on_planes = false;
  const std::optional<Snap> point = snapCursor(registry_, camera_, at.x(), at.y(), no_points_, planes_only);
  ASSERT_TRUE(point);
  EXPECT_EQ(point->source, segments_[2]);
  // Far from every wall's line: the floor, seen face on.
  const Eigen::Vector2d middle = pixelOf({1.0, 1.0, 0.0});
  const std::optional<Snap> floor = snapCursor(registry_, camera_, middle.x(), middle.y(), no_points_, planes_only);
  ASSERT_TRUE(floor);
  EXPECT_EQ(floor->source, segments_[2]);
}

TEST_F(SnappingTest, OutsideEveryFeatureAPointOfTheCloudOrNothing) {
  const Eigen::Vector3d away(3.0, 3.0, 0.0);  // beyond the floor's outline
  const Eigen::Vector2d at = pixelOf(away);
  EXPECT_FALSE(snapCursor(registry_, camera_, at.x(), at.y(), no_points_));
  const PointPicker picks = [&](double, double) { return std::optional<Eigen::Vector3d>(away); };
  const std::optional<Snap> snap = snapCursor(registry_, camera_, at.x(), at.y(), picks);
  ASSERT_TRUE(snap);
  EXPECT_EQ(snap->kind, Snap::Kind::kPoint);
  EXPECT_EQ(snap->source, ecs::kNullEntity);
  EXPECT_STREQ(snapKindName(snap->kind), "point");
}

}  // namespace
}  // namespace plumb::viewer
