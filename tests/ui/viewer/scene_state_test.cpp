// The viewer's scene: live grow snapshots replace their entities, a final result becomes one
// undoable edit, a cancelled grow leaves nothing, deleting takes edges and corners along, and
// the JSON dump holds what the tests of the viewer read.

#include "ui/viewer/scene_state.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "ui/viewer/grow_session.h"
#include "ui/viewer/scene_overlay.h"

namespace plumb::viewer {
namespace {

reco::Plane planeWithNormal(const Eigen::Vector3d& normal, const Eigen::Vector3d& centroid) {
  reco::Plane plane;
  plane.valid = true;
  plane.normal = normal;
  plane.centroid = centroid;
  plane.offset = -normal.dot(centroid);
  plane.lambda2 = 4e-6;
  return plane;
}

// Three segments at a corner, with their edges and the corner.
GrowUpdate cornerUpdate(std::uint64_t grow, bool final) {
  GrowUpdate update;
  update.grow = grow;
  update.final = final;
  const std::array<Eigen::Vector3d, 3> normals{Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY(),
                                               Eigen::Vector3d::UnitZ()};
  for (const Eigen::Vector3d& normal : normals) {
    reco::SegmentSnapshot segment;
    segment.plane = planeWithNormal(normal, Eigen::Vector3d(1, 1, 1) - normal);
    segment.points = 1000;
    auto outline = std::make_shared<reco::PlaneOutline>();
    outline->shape.vertices = {{0, 0}, {1, 0}, {0, 1}};
    outline->shape.triangles = {{0, 1, 2}};
    outline->shape.rings = {{{0, 0}, {1, 0}, {0, 1}}};
    outline->shape.area_m2 = 0.5;
    segment.outline = outline;
    update.snapshot.segments.push_back(segment);
  }
  update.snapshot.edges.push_back({{0, 1}, {0, 0, 0}, {0, 0, 1}, {0, 0, 1}, 50});
  update.snapshot.edges.push_back({{1, 2}, {0, 0, 0}, {1, 0, 0}, {1, 0, 0}, 40});
  update.snapshot.corners.push_back({{0, 1, 2}, {0, 0, 0}, {1e-6, 2e-6, 3e-6}});
  update.snapshot.converged = final;
  return update;
}

TEST(SceneState, LiveSnapshotsReplaceTheirEntitiesUnrecorded) {
  SceneState scene;
  scene.applyGrow(cornerUpdate(1, false));
  scene.applyGrow(cornerUpdate(1, false));
  const ecs::Registry& registry = scene.registry();
  EXPECT_EQ(registry.count<Segment>(), 3u) << "the second snapshot replaced the first";
  EXPECT_EQ(registry.count<Edge>(), 2u);
  EXPECT_EQ(registry.count<Corner>(), 1u);
  EXPECT_EQ(registry.count<SnapCandidate>(), 3u);
  registry.view<Segment>().each([](ecs::Entity, const Segment& segment) { EXPECT_TRUE(segment.growing); });
  EXPECT_FALSE(scene.history().canUndo());
}

TEST(SceneState, AFinalResultIsOneUndoableEdit) {
  SceneState scene;
  scene.applyGrow(cornerUpdate(1, false));
  scene.applyGrow(cornerUpdate(1, true));
  const ecs::Registry& registry = scene.registry();
  ASSERT_EQ(registry.count<Segment>(), 3u);
  std::vector<std::string> names;
  registry.view<Segment>().each([&](ecs::Entity, const Segment& segment) {
    EXPECT_FALSE(segment.growing);
    EXPECT_DOUBLE_EQ(segment.area_m2, 0.5);
    names.push_back(segment.name);
  });
  EXPECT_EQ(names, (std::vector<std::string>{"Segment 1", "Segment 2", "Segment 3"}));
  ASSERT_TRUE(scene.history().canUndo());
  EXPECT_EQ(scene.history().undoName(), "Grow");
  scene.history().undo();
  EXPECT_EQ(registry.count<Segment>(), 0u);
  EXPECT_EQ(registry.count<Corner>(), 0u);
  scene.history().redo();
  EXPECT_EQ(registry.count<Segment>(), 3u);
  EXPECT_EQ(registry.count<Edge>(), 2u);
}

TEST(SceneState, ACancelledGrowLeavesNothing) {
  SceneState scene;
  scene.applyGrow(cornerUpdate(1, false));
  GrowUpdate cancelled = cornerUpdate(1, true);
  cancelled.snapshot.cancelled = true;
  scene.applyGrow(cancelled);
  EXPECT_EQ(scene.registry().count<Segment>(), 0u);
  EXPECT_EQ(scene.registry().count<Edge>(), 0u);
  EXPECT_FALSE(scene.history().canUndo());
}

TEST(SceneState, GrowsAccumulateAndANewClickDropsOnlyTheLiveOne) {
  SceneState scene;
  scene.applyGrow(cornerUpdate(1, true));
  scene.applyGrow(cornerUpdate(2, false));
  EXPECT_EQ(scene.registry().count<Segment>(), 6u);
  scene.dropLive();
  EXPECT_EQ(scene.registry().count<Segment>(), 3u);
}

// A second click on the same corner (a final result whose three segments lie on the surfaces of
// the three kept): the kept segments are refined, keeping their names, with the new result's
// edges and corners; one undo brings back the first result's planes, edges and corner.
TEST(SceneState, ASecondGrowOnTheSameSurfacesRefinesTheirSegments) {
  SceneState scene;
  scene.applyGrow(cornerUpdate(1, true));
  GrowUpdate again = cornerUpdate(2, true);
  for (reco::SegmentSnapshot& segment : again.snapshot.segments) {
    segment.points = 5000;                                   // finer detail
    segment.plane.centroid += 0.001 * segment.plane.normal;  // within t_p of the first
    segment.plane.offset = -segment.plane.normal.dot(segment.plane.centroid);
  }
  again.snapshot.plane_threshold_m = 0.02;
  again.snapshot.search_radius_m = 0.1;
  again.snapshot.corners[0].position = {0.001, 0.001, 0.001};
  scene.applyGrow(again);
  const ecs::Registry& registry = scene.registry();
  ASSERT_EQ(registry.count<Segment>(), 3u) << "no copies";
  EXPECT_EQ(registry.count<Edge>(), 2u);
  ASSERT_EQ(registry.count<Corner>(), 1u);
  std::vector<std::string> names;
  registry.view<Segment>().each([&](ecs::Entity, const Segment& segment) {
    EXPECT_EQ(segment.points, 5000u);
    EXPECT_EQ(segment.grow, 2u);
    names.push_back(segment.name);
  });
  EXPECT_EQ(names, (std::vector<std::string>{"Segment 1", "Segment 2", "Segment 3"}));
  registry.view<Corner>().each([](ecs::Entity, const Corner& corner) { EXPECT_DOUBLE_EQ(corner.position.x(), 0.001); });

  ASSERT_TRUE(scene.history().undo());
  ASSERT_EQ(registry.count<Segment>(), 3u);
  registry.view<Segment>().each([](ecs::Entity, const Segment& segment) { EXPECT_EQ(segment.points, 1000u); });
  EXPECT_EQ(registry.count<Edge>(), 2u);
  registry.view<Corner>().each([](ecs::Entity, const Corner& corner) { EXPECT_DOUBLE_EQ(corner.position.x(), 0.0); });

  // A parallel surface 10 cm away is another surface: a segment of its own.
  scene.history().redo();
  GrowUpdate behind = cornerUpdate(3, true);
  behind.snapshot.segments.resize(1);
  behind.snapshot.edges.clear();
  behind.snapshot.corners.clear();
  behind.snapshot.segments[0].plane = planeWithNormal(Eigen::Vector3d::UnitX(), Eigen::Vector3d(-0.1, 1, 1));
  behind.snapshot.plane_threshold_m = 0.02;
  scene.applyGrow(behind);
  EXPECT_EQ(registry.count<Segment>(), 4u);
}

TEST(SceneState, DeletingASegmentTakesItsEdgesAndCornersAndUndoes) {
  SceneState scene;
  scene.applyGrow(cornerUpdate(1, true));
  ecs::Registry& registry = scene.registry();
  ecs::Entity first = ecs::kNullEntity;
  registry.view<Segment>().each([&](ecs::Entity entity, const Segment& segment) {
    if (segment.name == "Segment 1") first = entity;
  });
  ASSERT_NE(first, ecs::kNullEntity);
  registry.emplace(first, Selection{});
  EXPECT_EQ(scene.deleteSelected(), 1u);
  EXPECT_EQ(registry.count<Segment>(), 2u);
  EXPECT_EQ(registry.count<Edge>(), 1u) << "the edge between segments 2 and 3 stays";
  EXPECT_EQ(registry.count<Corner>(), 0u);
  EXPECT_EQ(scene.history().undoName(), "Delete segment");
  scene.history().undo();
  EXPECT_TRUE(registry.alive(first));
  EXPECT_EQ(registry.count<Edge>(), 2u);
  EXPECT_EQ(registry.count<Corner>(), 1u);
  EXPECT_EQ(scene.deleteSelected(), 1u) << "undo brought the selection back too";
}

TEST(SceneState, TheDumpHoldsPlanesEdgesAndCorners) {
  SceneState scene;
  scene.applyGrow(cornerUpdate(1, true));
  const nlohmann::json dump = nlohmann::json::parse(scene.toJson());
  ASSERT_EQ(dump.at("segments").size(), 3u);
  const nlohmann::json& segment = dump.at("segments")[0];
  EXPECT_EQ(segment.at("normal").size(), 3u);
  EXPECT_EQ(segment.at("points").get<int>(), 1000);
  EXPECT_FALSE(segment.at("growing").get<bool>());
  EXPECT_EQ(dump.at("edges").size(), 2u);
  ASSERT_EQ(dump.at("corners").size(), 1u);
  EXPECT_EQ(dump.at("corners")[0].at("segments").size(), 3u);
  EXPECT_TRUE(dump.at("measurements").empty());
}

TEST(SceneOverlay, DrawsTheSceneAndIsRebuiltOnlyWhenItChanges) {
  SceneState scene;
  SceneOverlay overlay;
  const auto empty = overlay.update(scene.registry());
  EXPECT_TRUE(empty->empty());
  EXPECT_EQ(overlay.update(scene.registry()), empty) << "nothing changed: the same overlay";
  scene.applyGrow(cornerUpdate(1, true));
  const auto drawn = overlay.update(scene.registry());
  EXPECT_NE(drawn, empty);
  EXPECT_EQ(drawn->polygons.size(), 3u);
  EXPECT_EQ(drawn->markers.size(), 1u) << "the corner";
  EXPECT_EQ(drawn->lines.size(), 3u * 3u + 2u) << "three outline edges per segment and two edges";
}

}  // namespace
}  // namespace plumb::viewer
