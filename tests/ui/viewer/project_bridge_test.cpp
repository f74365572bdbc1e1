// The viewer's scene as a project and back: what Save writes is what opening the project brings
// back, references (a polygon's plane, an edge's segments, groups) included, and the names go on
// counting after the project's.

#include "ui/viewer/project_bridge.h"

#include <gtest/gtest.h>

#include "cad/project_file.h"
#include "tests/support/temp_directory.h"
#include "tests/ui/viewer/room_corner.h"
#include "ui/viewer/components.h"
#include "ui/viewer/scene_state.h"

namespace plumb::viewer {
namespace {

TEST(ProjectBridge, ASceneSavedAndOpenedAgainIsTheSame) {
  SceneState scene;
  const fixtures::RoomCorner room = fixtures::makeRoomCorner(scene.registry());
  const ecs::Entity floor = room.segments[2];
  const ecs::Entity slab =
      scene.addPolygon({{0.2, 0.2, 0.0}, {1.0, 0.2, 0.0}, {1.0, 1.0, 0.0}, {0.2, 1.0, 0.0}}, floor);
  scene.extrudePolygon(slab, {0.0, 0.0, 0.3});
  scene.select(slab, false);
  scene.select(floor, true);
  const ecs::Entity group = scene.groupSelected();
  scene.rename(group, "ground floor");

  view::Camera camera;
  camera.position = {5, 5, 5};
  const cad::Project saved = projectOf(scene.registry(), "/data/room.plumb", camera);
  ASSERT_EQ(saved.segments.size(), 3u);
  ASSERT_EQ(saved.edges.size(), 1u);
  ASSERT_EQ(saved.corners.size(), 1u);
  ASSERT_EQ(saved.polygons.size(), 1u);
  ASSERT_EQ(saved.groups.size(), 1u);
  const test::TempDirectory dir;
  cad::writeProjectFile(saved, dir.file("room.plumbproj"));
  const cad::Project opened = cad::readProjectFile(dir.file("room.plumbproj"));
  EXPECT_EQ(opened.cloud_path, "/data/room.plumb");
  ASSERT_TRUE(opened.camera);
  EXPECT_EQ(opened.camera->position, camera.position);

  SceneState loaded;
  loadProject(opened, loaded);
  const ecs::Registry& registry = loaded.registry();
  EXPECT_EQ(registry.count<Segment>(), 3u);
  EXPECT_EQ(registry.count<Edge>(), 1u);
  EXPECT_EQ(registry.count<Corner>(), 1u);
  EXPECT_EQ(registry.count<SnapCandidate>(), 2u) << "the edge and the corner snap again";
  EXPECT_FALSE(loaded.history().canUndo()) << "opening is not an edit";
  registry.view<Polygon>().each([&](ecs::Entity entity, const Polygon& polygon) {
    EXPECT_EQ(polygon.name, "Polygon 1");
    EXPECT_EQ(polygon.vertices[2], Eigen::Vector3d(1.0, 1.0, 0.0));
    EXPECT_EQ(polygon.extrusion, Eigen::Vector3d(0.0, 0.0, 0.3));
    ASSERT_TRUE(registry.has<Segment>(polygon.plane)) << "its plane is the floor again";
    EXPECT_EQ(registry.get<Segment>(polygon.plane).plane.normal, Eigen::Vector3d::UnitZ());
    ASSERT_TRUE(registry.has<InGroup>(entity));
    EXPECT_EQ(registry.get<Group>(registry.get<InGroup>(entity).group).name, "ground floor");
  });
  registry.view<Corner>().each([&](ecs::Entity, const Corner& corner) {
    for (const ecs::Entity segment : corner.segments) EXPECT_TRUE(registry.has<Segment>(segment));
  });
  // The next polygon is number 2, not another "Polygon 1".
  const ecs::Entity next = loaded.addPolygon({{0, 0, 1}, {1, 0, 1}, {1, 1, 1}}, ecs::kNullEntity);
  EXPECT_EQ(loaded.registry().get<Polygon>(next).name, "Polygon 2");
  // Saved again, the same project.
  loaded.history().undo();
  const cad::Project again = projectOf(loaded.registry(), opened.cloud_path, opened.camera);
  EXPECT_EQ(again.polygons.size(), 1u);
  EXPECT_EQ(again.polygons[0].vertices, saved.polygons[0].vertices);
  EXPECT_EQ(again.segments[2].plane.centroid, saved.segments[2].plane.centroid);
}

TEST(ProjectBridge, ALiveGrowAndDanglingReferencesAreNotSaved) {
  SceneState scene;
  const fixtures::RoomCorner room = fixtures::makeRoomCorner(scene.registry());
  scene.registry().patch<Segment>(room.segments[0], [](Segment& s) { s.growing = true; });
  const ecs::Entity polygon = scene.addPolygon({{0.2, 0.2, 0.0}, {1.0, 0.2, 0.0}, {1.0, 1.0, 0.0}}, room.segments[2]);
  scene.select(room.segments[2], false);
  scene.deleteSelected();  // the floor goes, with the corner; the polygon stays
  const cad::Project project = projectOf(scene.registry(), "", std::nullopt);
  EXPECT_EQ(project.segments.size(), 1u) << "the growing wall and the deleted floor are not in it";
  EXPECT_TRUE(project.edges.empty()) << "the edge of the growing wall";
  EXPECT_TRUE(project.corners.empty());
  ASSERT_EQ(project.polygons.size(), 1u);
  EXPECT_EQ(project.polygons[0].plane, cad::kNoItem) << "its plane was deleted";
  EXPECT_TRUE(scene.registry().alive(polygon));
}

}  // namespace
}  // namespace plumb::viewer
