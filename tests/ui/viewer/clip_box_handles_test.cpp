// The clip box's handles dragged as the viewer drags them: pressed at the pixel where a handle
// appears, moved to the pixel where a world point appears; the box must follow exactly.

#include "ui/viewer/clip_box_handles.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace plumb::viewer {
namespace {

constexpr double kExact = 1e-9;

class ClipBoxHandlesTest : public ::testing::Test {
 protected:
  void SetUp() override {
    box_.centre = {10.0, 5.0, 1.0};
    box_.half_size = {2.0, 1.0, 1.0};
    camera_.position = {10.0, -10.0, 6.0};
    camera_.target = {10.0, 5.0, 1.0};
    camera_.viewport_width_px = 800;
    camera_.viewport_height_px = 600;
  }

  view::Ray rayAt(const Eigen::Vector3d& world) const {
    const Eigen::Vector2d pixel = *view::pixelOf(camera_, world);
    return view::rayThroughPixel(camera_, pixel.x(), pixel.y());
  }
  Eigen::Vector3d handle(BoxHandle h) const { return boxHandlePositions(box_)[static_cast<std::size_t>(h)]; }
  // Pressed on handle `h`, moved to where `to` appears.
  view::ClipBox drag(BoxHandle h, const Eigen::Vector3d& to, bool vertical = false) const {
    const Eigen::Vector2d pixel = *view::pixelOf(camera_, handle(h));
    EXPECT_EQ(boxHandleAt(box_, camera_, pixel.x(), pixel.y()), h);
    return BoxDrag(box_, h, rayAt(handle(h)), vertical).boxFor(rayAt(to));
  }

  view::ClipBox box_;
  view::Camera camera_;
};

TEST_F(ClipBoxHandlesTest, AFaceMovesAndTheOppositeFaceStays) {
  const view::ClipBox wider = drag(BoxHandle::kXMax, {13.0, 5.0, 1.0});
  EXPECT_NEAR(wider.half_size.x(), 2.5, kExact);
  EXPECT_NEAR(wider.centre.x(), 10.5, kExact);
  EXPECT_NEAR(wider.centre.x() - wider.half_size.x(), 8.0, kExact) << "the x- face stays";
  EXPECT_NEAR((wider.centre - Eigen::Vector3d(10.5, 5.0, 1.0)).norm(), 0.0, kExact);
  const view::ClipBox lower = drag(BoxHandle::kZMin, {10.0, 5.0, -0.5});
  EXPECT_NEAR(lower.half_size.z(), 1.25, kExact);
  EXPECT_NEAR(lower.centre.z() + lower.half_size.z(), 2.0, kExact) << "the top stays";
  // Past the opposite face: the box keeps its least thickness against that face.
  const view::ClipBox crushed = drag(BoxHandle::kYMin, {10.0, 9.0, 1.0});
  EXPECT_NEAR(crushed.half_size.y(), kMinBoxHalfSize, kExact);
  EXPECT_NEAR(crushed.centre.y() + crushed.half_size.y(), 6.0, kExact);
}

TEST_F(ClipBoxHandlesTest, TheCentreMovesLevelOrWithShiftUpAndDown) {
  const view::ClipBox moved = drag(BoxHandle::kCentre, {11.5, 6.25, 1.0});
  EXPECT_NEAR((moved.centre - Eigen::Vector3d(11.5, 6.25, 1.0)).norm(), 0.0, kExact);
  EXPECT_EQ(moved.half_size, box_.half_size);
  const view::ClipBox raised = drag(BoxHandle::kCentre, {10.0, 5.0, 1.75}, true);
  EXPECT_NEAR((raised.centre - Eigen::Vector3d(10.0, 5.0, 1.75)).norm(), 0.0, kExact);
}

TEST_F(ClipBoxHandlesTest, TheTurnHandleTurnsAboutTheVerticalAndFacesFollowTheTurn) {
  const Eigen::Vector3d from = handle(BoxHandle::kTurn);
  const double angle = 30.0 * std::numbers::pi / 180.0;
  const Eigen::Vector3d arm = from - box_.centre;
  const Eigen::Vector3d to =
      box_.centre + Eigen::Vector3d(std::cos(angle) * arm.x() - std::sin(angle) * arm.y(),
                                    std::sin(angle) * arm.x() + std::cos(angle) * arm.y(), arm.z());
  const view::ClipBox turned = drag(BoxHandle::kTurn, to);
  EXPECT_NEAR(turned.yaw_rad, angle, kExact);
  EXPECT_EQ(turned.centre, box_.centre);
  // The turned box's x+ face moves along its own axis.
  box_ = turned;
  const Eigen::Vector3d axis(std::cos(angle), std::sin(angle), 0.0);
  const view::ClipBox longer = drag(BoxHandle::kXMax, box_.centre + 3.0 * axis);
  EXPECT_NEAR(longer.half_size.x(), 2.5, kExact);
  EXPECT_NEAR((longer.centre - (box_.centre + 0.5 * axis)).norm(), 0.0, kExact);
}

TEST_F(ClipBoxHandlesTest, HandlesAreFoundNearTheirMarkersOnly) {
  const Eigen::Vector2d face = *view::pixelOf(camera_, handle(BoxHandle::kYMin));
  EXPECT_EQ(boxHandleAt(box_, camera_, face.x() + 5.0, face.y() - 5.0), BoxHandle::kYMin);
  EXPECT_FALSE(boxHandleAt(box_, camera_, face.x() + 40.0, face.y()));
  // From straight above, the centre and the top face's handle share a pixel: the centre wins.
  camera_.position = {10.0, 5.0, 20.0};
  camera_.up = Eigen::Vector3d::UnitY();
  const Eigen::Vector2d centre = *view::pixelOf(camera_, box_.centre);
  EXPECT_EQ(boxHandleAt(box_, camera_, centre.x(), centre.y()), BoxHandle::kCentre);
}

// Seen from straight above, the top face's handle runs along the view: a drag does not move it
// (nearly parallel, each pixel would move it metres).
TEST_F(ClipBoxHandlesTest, AHandleDraggedAlongTheViewStaysPut) {
  camera_.position = {10.0, 5.0, 20.0};
  camera_.up = Eigen::Vector3d::UnitY();
  const view::ClipBox same =
      BoxDrag(box_, BoxHandle::kZMax, rayAt(handle(BoxHandle::kZMax)), false).boxFor(rayAt({10.5, 5.5, 2.0}));
  EXPECT_EQ(same.centre, box_.centre);
  EXPECT_EQ(same.half_size, box_.half_size);
}

TEST_F(ClipBoxHandlesTest, TwelveEdgesBetweenEightCorners) {
  double length = 0.0;
  for (const auto& [a, b] : boxEdges(box_)) length += (b - a).norm();
  EXPECT_NEAR(length, 4.0 * (4.0 + 2.0 + 2.0), kExact);
}

}  // namespace
}  // namespace plumb::viewer
