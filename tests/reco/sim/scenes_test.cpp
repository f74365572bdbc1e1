// The scenes' ground truth is consistent with their geometry: every corner and edge lies on its
// planes and on surfaces that were actually built.

#include "reco/sim/scenes.h"

#include <gtest/gtest.h>

#include "engine/core/error.h"
#include "reco/sim/ray_caster.h"

namespace plumb::reco::sim {
namespace {

double planeDistance(const TruthPlane& plane, const Eigen::Vector3d& x) {
  return plane.normal.dot(x) + plane.offset;
}

// True when some rectangle of `plane` covers x (its border included, holes excluded).
bool onBuiltSurface(const Scene& scene, PlaneId plane, const Eigen::Vector3d& x) {
  constexpr double kTolerance = 1e-9;
  for (const Quad& q : scene.quads) {
    if (q.plane != plane) continue;
    const double u = x[(q.axis + 1) % 3], v = x[(q.axis + 2) % 3];
    if (u >= q.extent.u0 - kTolerance && u <= q.extent.u1 + kTolerance && v >= q.extent.v0 - kTolerance &&
        v <= q.extent.v1 + kTolerance) {
      return true;
    }
  }
  return false;
}

class SceneTruth : public ::testing::TestWithParam<std::string> {};

TEST_P(SceneTruth, PlanesAreUnitAndIndexedByTheirId) {
  const Scene scene = makeScene(GetParam());
  ASSERT_FALSE(scene.planes.empty());
  for (std::size_t i = 0; i < scene.planes.size(); ++i) {
    EXPECT_EQ(scene.planes[i].id, i);
    EXPECT_NEAR(scene.planes[i].normal.norm(), 1.0, 1e-15);
    EXPECT_FALSE(scene.planes[i].name.empty());
  }
  for (const Quad& q : scene.quads) {
    ASSERT_LT(q.plane, scene.planes.size());
    ASSERT_LT(q.material, scene.materials.size());
  }
}

TEST_P(SceneTruth, CornersLieOnTheirThreePlanesAndOnBuiltSurfaces) {
  const Scene scene = makeScene(GetParam());
  ASSERT_FALSE(scene.corners.empty());
  for (const TruthCorner& corner : scene.corners) {
    for (PlaneId id : corner.planes) {
      EXPECT_NEAR(planeDistance(scene.planes[id], corner.position), 0.0, 1e-12) << scene.planes[id].name;
      EXPECT_TRUE(onBuiltSurface(scene, id, corner.position))
          << "corner " << corner.position.transpose() << " is not on a built part of " << scene.planes[id].name;
    }
  }
}

TEST_P(SceneTruth, EdgesLieOnTheirTwoPlanesAndOnBuiltSurfaces) {
  const Scene scene = makeScene(GetParam());
  ASSERT_FALSE(scene.edges.empty());
  for (const TruthEdge& edge : scene.edges) {
    EXPECT_GT((edge.end - edge.start).norm(), 0.0);
    for (PlaneId id : edge.planes) {
      for (const Eigen::Vector3d& x : {edge.start, edge.end, Eigen::Vector3d(0.5 * (edge.start + edge.end))}) {
        EXPECT_NEAR(planeDistance(scene.planes[id], x), 0.0, 1e-12);
        EXPECT_TRUE(onBuiltSurface(scene, id, x)) << "edge point " << x.transpose() << " off " << scene.planes[id].name;
      }
    }
  }
}

TEST_P(SceneTruth, StationsStandInsideTheScene) {
  const Scene scene = makeScene(GetParam());
  ASSERT_GE(scene.stations.size(), scene.default_station_count);
  const RayCaster caster(scene);
  for (const Eigen::Vector3d& station : scene.stations) {
    RayHit hit;
    EXPECT_TRUE(caster.intersect(station, {0, 0, -1}, 100, hit)) << "nothing below station " << station.transpose();
    EXPECT_GT(hit.distance, 0.5);
  }
}

INSTANTIATE_TEST_SUITE_P(AllScenes, SceneTruth, ::testing::ValuesIn(sceneNames()));

TEST(Scenes, RoomCornersComeFirst) {
  const Scene room = roomScene();
  ASSERT_GE(room.corners.size(), 8u);
  for (int i = 0; i < 8; ++i) {
    const Eigen::Vector3d& p = room.corners[static_cast<std::size_t>(i)].position;
    EXPECT_TRUE(p.x() == 0 || p.x() == 7) << p.transpose();
    EXPECT_TRUE(p.y() == 0 || p.y() == 5) << p.transpose();
    EXPECT_TRUE(p.z() == 0 || p.z() == 2.5) << p.transpose();
  }
}

TEST(Scenes, UnknownNameIsAnError) {
  EXPECT_THROW(makeScene("castle"), Error);
}

// A turn of 30 degrees about z (counter-clockwise seen from above), then the offset: checked on
// its own, since planes and points turned by no angle at all would stay consistent too.
TEST(SceneFrame, TurnsAboutTheVerticalThenOffsets) {
  const SceneFrame frame{30.0, {512000, 5403000, 250}};
  const Eigen::Vector3d world = frame.toWorld({1.0, 0.0, 2.0});
  EXPECT_NEAR(world.x() - 512000, std::sqrt(3.0) / 2.0, 1e-9);
  EXPECT_NEAR(world.y() - 5403000, 0.5, 1e-9);
  EXPECT_NEAR(world.z() - 250, 2.0, 1e-9);
  const TruthPlane wall = frame.toWorld(TruthPlane{.id = 0, .name = "x = 1", .normal = {1.0, 0.0, 0.0}, .offset = -1.0});
  EXPECT_NEAR(wall.normal.x(), std::sqrt(3.0) / 2.0, 1e-12);
  EXPECT_NEAR(wall.normal.y(), 0.5, 1e-12);
  EXPECT_NEAR(wall.normal.dot(world) + wall.offset, 0.0, 1e-8) << "the turned point lies on the turned plane x = 1";
}

TEST(SceneFrame, RotatesPlanesAndPointsConsistently) {
  const SceneFrame frame{30.0, {512000, 5403000, 250}};
  const Scene room = roomScene();
  for (const TruthCorner& corner : room.corners) {
    for (PlaneId id : corner.planes) {
      const TruthPlane world = frame.toWorld(room.planes[id]);
      EXPECT_NEAR(world.normal.dot(frame.toWorld(corner.position)) + world.offset, 0.0, 1e-8);
    }
  }
}

}  // namespace
}  // namespace plumb::reco::sim
