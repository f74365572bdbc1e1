// The expert tasks of paper section 5 (issue 7, point 10), done in `plumb view` as a user does
// them: scripted grows, selections, drawing tools and typed input on simulated scans at UTM-like
// coordinates, each result checked against the simulator's ground truth, within a few times the
// statistical limit of the scan there (tests/support/simulated_truth.h).
//
//   (a) a wall rectangle whose corner lies in a scan shadow, the corner made of three planes
//   (b) a window reveal extruded from its top face down to its sill: a closed prism
//   (c) a stair tread copied up the staircase along a locked direction, then spread evenly
//
// PLUMB_TEST_SCREENSHOTS=DIR keeps the screenshots.

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <algorithm>
#include <cstdio>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "tests/support/simulated_truth.h"
#include "tests/support/temp_directory.h"
#include "tests/ui/viewer_session.h"

namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using plumb::test::jsonPoint;
using plumb::test::readJson;
using plumb::test::vector3;

const Eigen::Vector3d kOffset(512000.0, 5403000.0, 250.0);

// A point of the scene's frame in world coordinates, as a script takes it.
json at(double x, double y, double z) {
  return jsonPoint(kOffset + Eigen::Vector3d(x, y, z));
}
json look(const Eigen::Vector3d& position, const Eigen::Vector3d& target) {
  return {{"look", {{"position", jsonPoint(kOffset + position)}, {"target", jsonPoint(kOffset + target)}}}};
}
json frames(int count) {
  return {{"wait", "frames"}, {"count", count}};
}
const json kGrowerIdle = {{"wait", "grower_idle"}, {"timeout_s", 300}};
const json kStreamingIdle = {{"wait", "streaming_idle"}, {"timeout_s", 300}};

// A grow seeded at `seed`, seen from `eye` (near: the detail of a zoomed-in view).
void growAt(json& steps, const Eigen::Vector3d& eye, const Eigen::Vector3d& seed) {
  steps.push_back(look(eye, seed));
  steps.push_back(kStreamingIdle);
  steps.push_back({{"click_world", at(seed.x(), seed.y(), seed.z())}});
  steps.push_back(kGrowerIdle);
}

// Simulates `scene` into the test's folder (scene.ply with its truth scene.json) and imports it
// (an octree opens at once).
std::string simulated(const plumb::test::TempDirectory& dir, const std::string& scene, const std::string& options) {
  const std::string ply = dir.file(scene + ".ply"), octree = dir.file(scene + ".plumb");
  const std::string command = std::string("'") + PLUMB_BINARY + "' simulate --scene " + scene + " " + options +
                              " --noise-mm 2 --offset 512000,5403000,250 -o '" + ply + "' --truth '" +
                              dir.file(scene + ".json") + "' >/dev/null && '" + PLUMB_BINARY + "' import '" + ply +
                              "' -o '" + octree + "' >/dev/null";
  EXPECT_EQ(std::system(command.c_str()), 0) << command;
  return octree;
}

// What a vertex snapped to the true corner `local` (scene frame) may be off: `factor` times the
// statistical limit of the scan there.
double allowedAt(const plumb::test::SimulatedTruth& truth, const Eigen::Vector3d& local,
                 double factor = plumb::test::kEndToEndLimitFactor) {
  return factor * truth.cornerLimit(kOffset + local).standard_error_m;
}

// The scene frame's point `local` against a world position: the distance in metres.
double distance(const json& world, const Eigen::Vector3d& local) {
  return (vector3(world) - (kOffset + local)).norm();
}

// (a) With one station, the room's corner at (0, 5, 0) lies behind the cabinet: no point within
// 15 cm. Grows at the other corners and on the y+ wall give the planes; the corner where the
// floor, the x- wall and the y+ wall meet is made from the three selected segments, and the
// wall's rectangle is drawn through it.
TEST(ExpertTasks, AWallRectangleClosedThroughACornerInAScanShadow) {
  const plumb::test::TempDirectory dir;
  const std::string cloud = simulated(dir, "room", "--stations 1 --points 1000000");
  json steps = json::array({kStreamingIdle, {{"tool", "grow"}}});
  growAt(steps, {1.6, 1.6, 1.2}, {0.2, 0.2, 0.0});  // the corner (0, 0, 0): floor, x- and y- walls
  growAt(steps, {1.6, 1.6, 1.3}, {0.2, 0.2, 2.5});  // the corner (0, 0, 2.5): the ceiling
  growAt(steps, {2.0, 2.5, 1.5}, {2.0, 5.0, 1.5});  // the y+ wall, beside the cabinet
  steps.push_back(look({6.3, 2.5, 1.4}, {0.0, 2.5, 1.25}));
  steps.push_back(kStreamingIdle);
  // Two corners of three selected segments: floor or ceiling, the x- wall, the y+ wall.
  steps.push_back({{"tool", "navigate"}});
  for (const json& horizontal : {at(1.0, 2.5, 0.0), at(1.0, 2.5, 2.5)}) {
    steps.push_back({{"click_world", horizontal}});
    steps.push_back({{"key_down", "LEFT_CONTROL"}});
    steps.push_back({{"click_world", at(0.0, 2.5, 1.0)}});
    steps.push_back({{"click_world", at(1.5, 5.0, 2.3)}});
    steps.push_back({{"key_up", "LEFT_CONTROL"}});
    steps.push_back({{"key", "K"}});
    steps.push_back(frames(2));
  }
  steps.push_back({{"tool", "polygon"}});
  const std::vector<Eigen::Vector3d> wall{{0, 0, 0}, {0, 5, 0}, {0, 5, 2.5}, {0, 0, 2.5}};
  for (const Eigen::Vector3d& corner : wall) {
    steps.push_back({{"click_world", at(corner.x(), corner.y(), corner.z())}});
    steps.push_back(frames(2));
  }
  steps.push_back({{"move_world", at(0, 0, 0)}});
  steps.push_back(frames(2));
  steps.push_back({{"screenshot", "a-closing.png"}});
  steps.push_back({{"click_world", at(0, 0, 0)}});  // the first vertex again: closes
  steps.push_back(frames(2));
  steps.push_back({{"screenshot", "a-wall.png"}});
  ASSERT_EQ(plumb::test::runViewerSession(dir, "'" + cloud + "'", steps), 0);
  plumb::test::keepScreenshots(dir);

  const json scene = readJson(dir.file("scene.json"));
  const json* shadow_corner = nullptr;
  for (const json& corner : scene.at("corners")) {
    if (corner.at("name") == "Corner 1") shadow_corner = &corner;
  }
  ASSERT_NE(shadow_corner, nullptr) << "no corner was made of the three selected segments";
  const plumb::test::SimulatedTruth truth(dir.file("room.ply"), dir.file("room.json"));
  const double shadow_error = distance(shadow_corner->at("position"), {0, 5, 0});
  const double shadow_allowed = allowedAt(truth, {0, 5, 0});
  std::printf("the corner in the scan shadow: %.3f mm from the truth (allowed %.3f mm)\n", shadow_error * 1e3,
              shadow_allowed * 1e3);
  EXPECT_LT(shadow_error, shadow_allowed);
  ASSERT_EQ(scene.at("polygons").size(), 1u);
  const json& vertices = scene.at("polygons")[0].at("vertices");
  ASSERT_EQ(vertices.size(), 4u);
  for (std::size_t i = 0; i < 4; ++i) {
    const double error = distance(vertices[i], wall[i]);
    const double allowed = allowedAt(truth, wall[i]);
    std::printf("wall rectangle vertex %zu: %.3f mm from the truth (allowed %.3f mm)\n", i + 1, error * 1e3,
                allowed * 1e3);
    EXPECT_LT(error, allowed);
  }
}

// (b) The room's window recess (x 2.5 to 4.3, y 5 to 5.25, z 0.9 to 2.1): grows at three corners
// of its head (t_p 6 mm, three times the noise, as a surveyor sets it: the head is 25 cm deep),
// a rectangle through them, then an extrusion along the floor's normal (found by pointing at the
// floor, locked by Shift) down to the sill's plane. The prism's eight vertices must lie near
// the recess's (below). The project is saved and exported.
TEST(ExpertTasks, AWindowRevealExtrudedFromItsHeadToItsSill) {
  const plumb::test::TempDirectory dir;
  const std::string cloud = simulated(dir, "room", "--points 2000000");
  const std::string project = dir.file("window.plumbproj");
  json steps = json::array({kStreamingIdle, {{"tool", "grow"}}});
  growAt(steps, {2.9, 4.3, 1.7}, {2.58, 5.06, 2.1});  // on the head: head, x- reveal, wall
  growAt(steps, {3.9, 4.3, 1.7}, {4.22, 5.06, 2.1});  // head, x+ reveal, wall
  growAt(steps, {3.9, 4.3, 1.7}, {4.22, 5.19, 2.1});  // head, x+ reveal, glass
  growAt(steps, {3.4, 3.9, 1.5}, {3.4, 5.12, 0.9});   // the sill
  growAt(steps, {3.4, 3.0, 1.5}, {3.4, 4.3, 0.0});    // the floor, for the vertical
  steps.push_back(look({3.4, 2.9, 1.5}, {3.4, 5.0, 1.5}));
  steps.push_back(kStreamingIdle);
  steps.push_back({{"tool", "polygon"}});
  steps.push_back({{"key", "R"}});  // a rectangle from three points
  for (const json& corner : {at(2.5, 5.0, 2.1), at(4.3, 5.0, 2.1), at(4.3, 5.25, 2.1)}) {
    steps.push_back({{"click_world", corner}});
    steps.push_back(frames(2));
  }
  steps.push_back({{"tool", "extrude"}});
  steps.push_back({{"click_world", at(3.4, 5.125, 2.1)}});  // picks the rectangle
  steps.push_back(frames(2));
  // The vertical: the floor's normal (the sill is too small to give its own as precisely),
  // locked, then the sill's plane seen from above (from afar its edges lie within the snapping
  // radius of any point of it).
  steps.push_back(look({3.4, 3.4, 1.5}, {3.4, 4.3, 0.0}));
  steps.push_back(kStreamingIdle);
  steps.push_back({{"move_world", at(3.4, 4.3, 0.0)}});
  steps.push_back(frames(2));
  steps.push_back({{"key_down", "LEFT_SHIFT"}});
  steps.push_back(look({3.4, 4.4, 1.5}, {3.4, 5.12, 0.9}));
  steps.push_back(kStreamingIdle);
  steps.push_back({{"move_world", at(3.4, 5.12, 0.9)}});
  steps.push_back(frames(2));
  steps.push_back({{"screenshot", "b-extruding.png"}});
  steps.push_back({{"click_world", at(3.4, 5.12, 0.9)}});  // the sill's plane
  steps.push_back({{"key_up", "LEFT_SHIFT"}});
  steps.push_back(frames(2));
  steps.push_back(look({4.3, 3.2, 1.1}, {3.4, 5.1, 1.5}));
  steps.push_back(kStreamingIdle);
  steps.push_back({{"screenshot", "b-prism.png"}});
  steps.push_back({{"key_down", "LEFT_CONTROL"}});
  steps.push_back({{"key", "S"}});
  steps.push_back({{"key_up", "LEFT_CONTROL"}});
  ASSERT_EQ(plumb::test::runViewerSession(dir, "'" + cloud + "' --tp 0.006 --project '" + project + "'", steps), 0);
  plumb::test::keepScreenshots(dir);

  const json scene = readJson(dir.file("scene.json"));
  ASSERT_EQ(scene.at("polygons").size(), 1u);
  const json& prism = scene.at("polygons")[0];
  const Eigen::Vector3d extrusion = vector3(prism.at("extrusion"));
  ASSERT_GT(extrusion.norm(), 1.0) << "not extruded";
  std::printf("extrusion (%.4f, %.4f, %.4f) m\n", extrusion.x(), extrusion.y(), extrusion.z());
  for (const json& segment : scene.at("segments")) {
    const Eigen::Vector3d normal = vector3(segment.at("normal")), centroid = vector3(segment.at("centroid")) - kOffset;
    if (std::abs(normal.z()) > 0.9)
      std::printf("horizontal segment at z %.4f m (%d points)\n", centroid.z(), segment.at("points").get<int>());
  }
  const std::vector<Eigen::Vector3d> head{{2.5, 5.0, 2.1}, {4.3, 5.0, 2.1}, {4.3, 5.25, 2.1}, {2.5, 5.25, 2.1}};
  // The head is a strip 25 cm deep between the wall and the glass: its segment takes in points of
  // the faces along both long edges, which tilts its plane by about 0.4 degrees (the vertices
  // 0.8 to 0.9 mm up on the wall's side and down on the glass's). That is 4.7 to 5.7 times the
  // limit, more than the other tasks' 5, and what the grower still has to do on narrow faces
  // (issue 19, point 5): bounded at 7 times until then, where it was 5 mm.
  constexpr double kNarrowFaceFactor = 7.0;
  const plumb::test::SimulatedTruth truth(dir.file("room.ply"), dir.file("room.json"));
  ASSERT_EQ(prism.at("vertices").size(), 4u);
  for (std::size_t i = 0; i < 4; ++i) {
    const json& vertex = prism.at("vertices")[i];
    const Eigen::Vector3d sill = head[i] - Eigen::Vector3d(0, 0, 1.2);
    const double top = distance(vertex, head[i]);
    const double bottom = distance(jsonPoint(vector3(vertex) + extrusion), sill);
    const double top_allowed = allowedAt(truth, head[i], kNarrowFaceFactor);
    const double bottom_allowed = allowedAt(truth, sill, kNarrowFaceFactor);
    const Eigen::Vector3d off = (vector3(vertex) - kOffset - head[i]) * 1e3;
    std::printf("prism vertex %zu: head %.3f mm off (%+.3f, %+.3f, %+.3f; allowed %.3f), sill %.3f mm off (allowed %.3f)\n",
                i + 1, top * 1e3, off.x(), off.y(), off.z(), top_allowed * 1e3, bottom * 1e3, bottom_allowed * 1e3);
    EXPECT_LT(top, top_allowed);
    EXPECT_LT(bottom, bottom_allowed);
  }
  // Saved (Ctrl+S): the project reads back, and exports.
  const std::string exported = dir.file("window");
  const std::string command = std::string("'") + PLUMB_BINARY + "' export '" + project + "' --gltf '" + exported +
                              ".glb' --dxf '" + exported + ".dxf' --obj '" + exported + ".obj' --csv '" + exported +
                              ".csv' >/dev/null";
  EXPECT_EQ(std::system(command.c_str()), 0) << command;
  for (const char* extension : {".glb", ".dxf", ".obj", ".csv"}) {
    EXPECT_GT(fs::file_size(exported + extension), 100u) << extension;
  }
}

// (c) The stairs scene (risers every 0.28 m along x, 0.1875 m apart in height, 1.2 m wide): a
// rectangle on the third tread from its nosing, copied with Copy on along the direction from that
// nosing to the twelfth (found by pointing, locked by Shift) onto the twelfth tread's plane; then
// "/9" spreads eight more copies evenly between. Each copy's nosing vertex must lie near its step's
// true nosing, where no tread was grown: a copy k ninths of the way carries the errors of the two
// grown nosings in those shares, each allowed a few times its statistical limit.
TEST(ExpertTasks, AStairTreadCopiedUpTheStaircaseAlongALockedDirection) {
  const plumb::test::TempDirectory dir;
  const std::string cloud = simulated(dir, "stairs", "--points 2000000");
  const auto nosing = [](int step) { return Eigen::Vector3d(2.0 + (step - 1) * 0.28, 1.2, step * 0.1875); };
  json steps = json::array({kStreamingIdle, {{"tool", "grow"}}});
  growAt(steps, {2.9, 1.7, 0.9}, {2.6, 1.15, 0.56});   // step 3's nosing at the stair's side
  growAt(steps, {5.4, 1.7, 2.6}, {5.12, 1.15, 2.24});  // step 12's
  steps.push_back(look({1.6, 2.8, 2.6}, {3.9, 0.6, 1.3}));
  steps.push_back(kStreamingIdle);
  steps.push_back({{"tool", "polygon"}});
  steps.push_back({{"key", "R"}});
  // The nosing corner, a point of the nosing's edge, a point of the tread towards its back.
  for (const json& point : {at(2.56, 1.2, 0.5625), at(2.56, 0.2, 0.5625), at(2.8, 0.5, 0.5625)}) {
    steps.push_back({{"click_world", point}});
    steps.push_back(frames(2));
  }
  steps.push_back({{"tool", "move"}});
  steps.push_back({{"key", "C"}});                           // Copy
  steps.push_back({{"click_world", at(2.7, 0.6, 0.5625)}});  // picks the tread's rectangle
  steps.push_back(frames(2));
  steps.push_back({{"click_world", at(2.56, 1.2, 0.5625)}});  // the base: step 3's nosing
  steps.push_back(frames(2));
  steps.push_back({{"move_world", at(5.08, 1.2, 2.25)}});  // towards step 12's nosing
  steps.push_back(frames(2));
  steps.push_back({{"key_down", "LEFT_SHIFT"}});
  steps.push_back({{"move_world", at(5.2, 0.6, 2.25)}});
  steps.push_back(frames(2));
  steps.push_back({{"screenshot", "c-locked.png"}});
  steps.push_back({{"click_world", at(5.2, 0.6, 2.25)}});  // step 12's tread plane
  steps.push_back(frames(2));
  steps.push_back({{"key_up", "LEFT_SHIFT"}});
  steps.push_back({{"type", "/9"}});
  steps.push_back({{"key", "ENTER"}});
  steps.push_back(frames(2));
  steps.push_back({{"screenshot", "c-copies.png"}});
  ASSERT_EQ(plumb::test::runViewerSession(dir, "'" + cloud + "'", steps), 0);
  plumb::test::keepScreenshots(dir);

  const json scene = readJson(dir.file("scene.json"));
  ASSERT_EQ(scene.at("polygons").size(), 10u) << "the tread and nine copies";
  const plumb::test::SimulatedTruth truth(dir.file("stairs.ply"), dir.file("stairs.json"));
  const double first_allowed = allowedAt(truth, nosing(3)), last_allowed = allowedAt(truth, nosing(12));
  // Each step from 4 to 12 holds one copy, whose first vertex (the copied nosing corner) is there.
  for (int step = 4; step <= 12; ++step) {
    double nearest = std::numeric_limits<double>::infinity();
    for (const json& polygon : scene.at("polygons")) {
      nearest = std::min(nearest, distance(polygon.at("vertices")[0], nosing(step)));
    }
    const double share = (step - 3) / 9.0;
    const double allowed = (1.0 - share) * first_allowed + share * last_allowed;
    std::printf("step %d: the nearest copy's nosing %.3f mm from the truth (allowed %.3f mm)\n", step, nearest * 1e3,
                allowed * 1e3);
    EXPECT_LT(nearest, allowed) << "step " << step;
  }
}

}  // namespace
