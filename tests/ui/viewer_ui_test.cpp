// The viewer end to end, as a user drives it: `plumb view` on its demo under Xvfb, on lavapipe
// with validation on (any message fails the run), replaying a scripted session: wait for the
// view to load, click a corridor wall, wait for the grow to converge, take screenshots. The
// scene dump must hold a segment on the simulator's true wall within a few times the statistical
// limit of the wall's least-squares fit (tests/support/simulated_truth.h), in angle and offset.
//
// PLUMB_TEST_SCREENSHOTS=DIR keeps the screenshots there for a person to look at.

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "engine/io/png_image.h"
#include "tests/support/simulated_truth.h"
#include "tests/support/temp_directory.h"
#include "tests/ui/viewer_session.h"

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// The demo's corridor wall y+ (y = 2 m in the scene's frame), at a point the demo's first view
// shows: the script clicks where this point appears.
const Eigen::Vector3d kWallPoint(512003.0, 5403002.0, 251.3);

using plumb::test::readJson;
using plumb::test::vector3;

double differingPixels(const plumb::io::RgbaImage& a, const plumb::io::RgbaImage& b) {
  std::size_t differing = 0;
  for (int y = 0; y < a.height; ++y) {
    for (int x = 0; x < a.width; ++x) differing += a.pixel(x, y) != b.pixel(x, y);
  }
  return static_cast<double>(differing) / (static_cast<double>(a.width) * a.height);
}

TEST(Viewer, AClickOnTheDemoWallGrowsItsPlane) {
  const plumb::test::TempDirectory dir;
  const fs::path cache = dir.file("cache"), shots = dir.file("shots");
  const fs::path scene = dir.file("scene.json");
  const json steps = json::array({
      {{"wait", "streaming_idle"}, {"timeout_s", 300}},
      {{"screenshot", "1-demo.png"}},
      {{"click_world", json::array({kWallPoint.x(), kWallPoint.y(), kWallPoint.z()})}},
      {{"wait", "grower_idle"}, {"timeout_s", 300}},
      {{"wait", "frames"}, {"count", 2}},
      {{"screenshot", "2-grown.png"}},
      {{"key", "1"}},
      {{"wait", "streaming_idle"}, {"timeout_s", 300}},
      {{"screenshot", "3-top.png"}},
  });
  ASSERT_EQ(plumb::test::runViewerSession(dir, "", steps, 1280, 720, "XDG_CACHE_HOME='" + cache.string() + "'"), 0);
  plumb::test::keepScreenshots(dir);

  // The segment on the wall.
  const json dump = readJson(scene);
  const json truth = readJson(cache / "plumb" / "demo-office-1M-2mm-v1.truth.json");
  Eigen::Vector3d true_normal = Eigen::Vector3d::Zero();
  double true_d = 0.0;
  for (const json& plane : truth.at("planes")) {
    if (plane.at("name") == "corridor wall y+") {
      true_normal = vector3(plane.at("normal"));
      true_d = plane.at("d").get<double>();
    }
  }
  ASSERT_NEAR(true_normal.norm(), 1.0, 1e-9) << "the truth has no 'corridor wall y+'";
  const Eigen::Vector3d on_wall = kWallPoint - (true_normal.dot(kWallPoint) + true_d) * true_normal;
  // The demo's scan again, with the simulator's labels (the demo keeps only the octree): the same
  // request as ui/viewer/demo_scan.cpp makes, checked by its truth's point count.
  const fs::path ply = dir.file("office.ply"), office_truth = dir.file("office.json");
  const std::string simulate = std::string("'") + PLUMB_BINARY +
                               "' simulate --scene office --points 1000000 --noise-mm 2 --seed 1 "
                               "--offset 512000,5403000,250 -o '" +
                               ply.string() + "' --truth '" + office_truth.string() + "' >/dev/null";
  ASSERT_EQ(std::system(simulate.c_str()), 0);
  ASSERT_EQ(readJson(office_truth).at("points"), truth.at("points")) << "not the demo's scan";
  const plumb::test::PlaneLimit limit =
      plumb::test::SimulatedTruth(ply.string(), office_truth.string()).planeLimit("corridor wall y+", on_wall);
  const double max_angle_deg = plumb::test::kEndToEndLimitFactor * limit.angle_error_rad * 180.0 / M_PI;
  const double max_offset_m = plumb::test::kEndToEndLimitFactor * limit.distance_error_m;
  std::printf("the wall's limit: %.5f degrees, %.4f mm at the click; allowed %.5f degrees, %.4f mm\n",
              limit.angle_error_rad * 180.0 / M_PI, limit.distance_error_m * 1e3, max_angle_deg, max_offset_m * 1e3);
  bool found = false;
  for (const json& segment : dump.at("segments")) {
    const Eigen::Vector3d normal = vector3(segment.at("normal"));
    const Eigen::Vector3d centroid = vector3(segment.at("centroid"));
    const double angle_deg = std::acos(std::min(1.0, std::abs(normal.dot(true_normal)))) * 180.0 / M_PI;
    const double offset_m = std::abs(normal.dot(on_wall - centroid));  // the planes apart at the click
    std::printf("segment %s: %d points, %.5f degrees and %.4f mm off the wall\n",
                segment.at("name").get<std::string>().c_str(), segment.at("points").get<int>(), angle_deg,
                offset_m * 1e3);
    EXPECT_FALSE(segment.at("growing").get<bool>());
    found = found || (angle_deg <= max_angle_deg && offset_m <= max_offset_m);
  }
  EXPECT_TRUE(found) << "no segment within " << max_angle_deg << " degrees and " << max_offset_m * 1e3
                     << " mm of the corridor wall";

  // The screenshots: the window's size, and the grow's outline visible in the second.
  const plumb::io::RgbaImage demo = plumb::io::readPng((shots / "1-demo.png").string());
  const plumb::io::RgbaImage grown = plumb::io::readPng((shots / "2-grown.png").string());
  const plumb::io::RgbaImage top = plumb::io::readPng((shots / "3-top.png").string());
  EXPECT_EQ(demo.width, 1280);
  EXPECT_EQ(demo.height, 720);
  EXPECT_GT(differingPixels(demo, grown), 0.05) << "the grown segment should colour a good part of the view";
  EXPECT_GT(differingPixels(grown, top), 0.3) << "the top view should look different";
  if (const char* keep = std::getenv("PLUMB_TEST_SCREENSHOTS")) {
    fs::create_directories(keep);
    for (const auto& entry : fs::directory_iterator(shots)) {
      fs::copy_file(entry.path(), fs::path(keep) / entry.path().filename(), fs::copy_options::overwrite_existing);
    }
  }
}

json world(const Eigen::Vector3d& p) {
  return json::array({p.x(), p.y(), p.z()});
}

// A point file, imported on a background job while the window shows the progress, opened in a
// camera file's view: a click near a room corner grows its two walls and the ceiling, and the
// corner they make lies on the simulator's. Then every kind of measurement, as a surveyor takes
// them: from the corner to the wall, the room's height between floor and ceiling, the angle of a
// wall to the floor, a point's distance to a wall, the corner's height above the floor, a drawn
// rectangle's area; each within a few times the statistical limit of the planes it was taken
// on, saved in the project and exported as CSV.
TEST(Viewer, APointFileIsImportedAndAClickNearACornerFindsIt) {
  const plumb::test::TempDirectory dir;
  const fs::path ply = dir.file("room.ply"), truth_path = dir.file("room.json");
  const std::string simulate =
      std::string("'") + PLUMB_BINARY + "' simulate --scene room --points 300000 --noise-mm 2 " +
      "--offset 512000,5403000,250 -o '" + ply.string() + "' --truth '" + truth_path.string() + "' >/dev/null";
  ASSERT_EQ(std::system(simulate.c_str()), 0);
  const fs::path camera = dir.file("camera.json"), scene = dir.file("scene.json");
  std::ofstream(camera) << R"({"format": "plumb-camera", "version": 1, "position": [512003.5, 5403002.5, 251.5],
                            "target": [512007.0, 5403005.0, 252.2], "fov_deg": 70, "viewport": [1280, 720]})";
  const Eigen::Vector3d offset(512000.0, 5403000.0, 250.0);
  const Eigen::Vector3d corner = offset + Eigen::Vector3d(7.0, 5.0, 2.5);
  const Eigen::Vector3d on_ceiling = corner + Eigen::Vector3d(-0.25, -0.25, 0.0);
  const Eigen::Vector3d on_wall = corner + Eigen::Vector3d(-2.0, 0.0, -1.0);  // the y+ wall, beside the window
  const Eigen::Vector3d on_wall_x = corner + Eigen::Vector3d(0.0, -0.8, -0.7);
  const Eigen::Vector3d on_floor = offset + Eigen::Vector3d(5.0, 3.0, 0.0);
  const json steps = json::array({
      {{"wait", "streaming_idle"}, {"timeout_s", 300}},
      {{"click_world", world(on_ceiling)}},
      {{"wait", "grower_idle"}, {"timeout_s", 300}},
      {{"wait", "frames"}, {"count", 2}},
      // Measure from the corner the planes make to the wall, snapped.
      {{"tool", "measure"}},
      {{"click_world", world(corner)}},
      {{"wait", "frames"}, {"count", 2}},
      {{"click_world", world(on_wall)}},
      {{"wait", "frames"}, {"count", 2}},
      // Level, from the room's middle: the floor, the ceiling and the x+ wall in view. The floor grows.
      {{"look",
        {{"position", world(offset + Eigen::Vector3d(1.0, 1.0, 1.25))},
         {"target", world(offset + Eigen::Vector3d(7.0, 5.0, 1.25))}}}},
      {{"wait", "streaming_idle"}, {"timeout_s", 300}},
      {{"tool", "grow"}},
      {{"click_world", world(on_floor)}},
      {{"wait", "grower_idle"}, {"timeout_s", 300}},
      {{"wait", "frames"}, {"count", 2}},
      {{"measure", "between_planes"}},
      {{"click_world", world(on_ceiling)}},
      {{"click_world", world(on_floor)}},
      {{"measure", "angle"}},
      {{"click_world", world(on_wall_x)}},
      {{"click_world", world(on_floor)}},
      {{"measure", "point_to_plane"}},
      {{"click_world", world(on_wall_x)}},
      {{"click_world", world(on_floor)}},
      {{"measure", "height"}},
      {{"wait", "ms"}, {"ms", 600}},  // two clicks on one place in a moment would be a double click (a focus)
      {{"click_world", world(on_floor)}},
      {{"click_world", world(corner)}},
      // A 1 m square on the floor (a rectangle from three points), and its area.
      {{"tool", "polygon"}},
      {{"key", "R"}},
      {{"click_world", world(on_floor + Eigen::Vector3d(-0.5, -0.5, 0.0))}},
      {{"click_world", world(on_floor + Eigen::Vector3d(0.5, -0.5, 0.0))}},
      {{"click_world", world(on_floor + Eigen::Vector3d(0.5, 0.5, 0.0))}},
      {{"measure", "area"}},
      {{"click_world", world(on_floor)}},
      {{"wait", "frames"}, {"count", 2}},
      {{"screenshot", "measurements.png"}},
      {{"key_down", "LEFT_CONTROL"}},
      {{"key", "S"}},
      {{"key", "E"}},
      {{"key_up", "LEFT_CONTROL"}},
  });
  // Built by appending: GCC 12 -O3 warns (-Wrestrict) on "'" + std::string.
  std::string arguments = "'";
  arguments += ply.string();
  arguments += "' --camera '";
  arguments += camera.string();
  arguments += "'";
  ASSERT_EQ(plumb::test::runViewerSession(dir, arguments, steps), 0);
  plumb::test::keepScreenshots(dir);
  const json dump = readJson(scene);
  ASSERT_GE(dump.at("segments").size(), 4u);
  // Within a few times the statistical limit of this scan at the corner (its three walls fitted
  // on all their true points, tests/support/simulated_truth.h).
  const plumb::test::SimulatedTruth simulated(ply.string(), truth_path.string());
  const plumb::test::CornerLimit limit = simulated.cornerLimit(corner);
  const double allowed_m = plumb::test::kEndToEndLimitFactor * limit.standard_error_m;
  double nearest_m = INFINITY;
  for (const json& found : dump.at("corners"))
    nearest_m = std::min(nearest_m, (vector3(found.at("position")) - corner).norm());
  std::printf(
      "%zu segments, %zu corners; the nearest %.4f mm from the true corner (the limit's standard error %.4f mm)\n",
      dump.at("segments").size(), dump.at("corners").size(), nearest_m * 1e3, limit.standard_error_m * 1e3);
  EXPECT_LT(nearest_m, allowed_m) << "no corner within " << allowed_m * 1e3 << " mm of the room's (2 mm noise)";

  const json& taken = dump.at("measurements");
  ASSERT_EQ(taken.size(), 6u) << taken.dump(1);
  const auto expectMeasured = [&](std::size_t i, const char* kind, double truth, double allowed) {
    const json& m = taken.at(i);
    EXPECT_EQ(m.at("kind"), kind);
    const double value = m.at("value").get<double>();
    std::printf("%s: %s, %.6f off the truth %.4f (allowed %.6f)\n", m.at("name").get<std::string>().c_str(),
                m.at("text").get<std::string>().c_str(), value - truth, truth, allowed);
    EXPECT_NEAR(value, truth, allowed) << m.dump();
  };
  const double k = plumb::test::kEndToEndLimitFactor;
  const plumb::test::PlaneLimit wall_y = simulated.planeLimit("room wall y+", on_wall);
  const plumb::test::PlaneLimit wall_x = simulated.planeLimit("room wall x+", on_wall_x);
  const plumb::test::PlaneLimit floor = simulated.planeLimit("room floor", on_floor);
  const plumb::test::PlaneLimit ceiling = simulated.planeLimit("room ceiling", on_ceiling);
  const double degrees = 180.0 / M_PI;
  // From the snapped corner to the y+ wall's plane: the corner's error and the wall's together.
  const json& from_corner = taken.at(0).at("sources").at(0);
  EXPECT_TRUE(std::any_of(dump.at("corners").begin(), dump.at("corners").end(),
                          [&](const json& c) { return c.at("id") == from_corner; }))
      << "taken on the corner: " << from_corner;
  expectMeasured(0, "distance", (on_wall - corner).norm(),
                 k * std::hypot(limit.standard_error_m, wall_y.distance_error_m));
  expectMeasured(1, "between_planes", 2.5, k * std::hypot(floor.distance_error_m, ceiling.distance_error_m));
  expectMeasured(2, "angle", 90.0, k * degrees * std::hypot(floor.angle_error_rad, wall_x.angle_error_rad));
  // The clicked point of the floor lies where the pixel's ray met the grown floor: its distance to
  // the true wall is the truth.
  const Eigen::Vector3d point = vector3(taken.at(3).at("from"));
  expectMeasured(3, "point_to_plane", std::abs(wall_x.normal.dot(point) + wall_x.d),
                 k * std::hypot(wall_x.distance_error_m, floor.distance_error_m));
  expectMeasured(4, "height", 2.5, k * std::hypot(limit.standard_error_m, floor.distance_error_m));
  // The drawn square: its vertices where the clicks met the floor, a pixel (about 8 mm here) apart
  // from where they were aimed.
  expectMeasured(5, "area", 1.0, 0.03);
  EXPECT_NEAR(taken.at(5).at("second").get<double>(), 4.0, 0.05) << "the perimeter";

  // Saved with the project, exported beside it.
  const json project = readJson(ply.string() + ".plumbproj");
  EXPECT_EQ(project.at("measurements").size(), 6u);
  const std::string csv = plumb::test::readFile(ply.string() + "-measurements.csv");
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 7) << csv;
  EXPECT_NE(csv.find(",between_planes,"), std::string::npos) << csv;
}

// A slice (plumb view --slice) keeps a band of the room: seen from above, a click on the
// ceiling's place finds nothing to grow (ceiling and floor are cut away, so nothing is picked),
// while a click on a wall inside the band grows the wall; Page Down steps the slice; X clips at
// the selected wall; the saved project keeps the slice and the plane.
TEST(Viewer, ASliceKeepsItsBandAndOnlyItsPointsArePicked) {
  const plumb::test::TempDirectory dir;
  const fs::path ply = dir.file("room.ply"), scene = dir.file("scene.json");
  const std::string simulate = std::string("'") + PLUMB_BINARY + "' simulate --scene room --points 200000 " +
                               "--noise-mm 2 -o '" + ply.string() + "' >/dev/null";
  ASSERT_EQ(std::system(simulate.c_str()), 0);
  const json steps = json::array({
      {{"wait", "streaming_idle"}, {"timeout_s", 300}},
      {{"key", "1"}},  // from above
      {{"wait", "streaming_idle"}, {"timeout_s", 300}},
      {{"click_world", json::array({3.5, 2.5, 2.5})}},  // the ceiling's middle: cut away
      {{"wait", "grower_idle"}, {"timeout_s", 300}},
      {{"key", "PAGE_DOWN"}},  // 1.05 to 1.15 m: the wall stays in the band
      {{"wait", "streaming_idle"}, {"timeout_s", 300}},
      {{"click_world", json::array({2.0, 5.0, 1.1})}},  // the y = 5 m wall, beside the window
      {{"wait", "grower_idle"}, {"timeout_s", 300}},
      {{"screenshot", "slice.png"}},
      // The wall selected (from the iso view: from above a wall is edge on), X: a clip plane on it
      // keeps the side the view is on, the room's.
      {{"key", "4"}},
      {{"wait", "streaming_idle"}, {"timeout_s", 300}},
      {{"tool", "navigate"}},
      {{"click_world", json::array({2.0, 5.0, 1.1})}},
      {{"key", "X"}},
      {{"key_down", "LEFT_CONTROL"}},
      {{"key", "S"}},  // the project keeps the section
      {{"key_up", "LEFT_CONTROL"}},
  });
  std::string arguments = "'";
  arguments += ply.string();
  arguments += "' --slice 1.15,0.1";
  ASSERT_EQ(plumb::test::runViewerSession(dir, arguments, steps, 1280, 720), 0);
  plumb::test::keepScreenshots(dir);
  const json dump = readJson(scene);
  ASSERT_GE(dump.at("segments").size(), 1u) << "the wall in the band grows";
  for (const json& segment : dump.at("segments")) {
    const Eigen::Vector3d normal = vector3(segment.at("normal"));
    EXPECT_LT(std::abs(normal.z()), 0.1) << "a horizontal plane was grown: " << segment.dump();
  }
  const json project = readJson(ply.string() + ".plumbproj");
  EXPECT_NEAR(project.at("section").at("slice").at("bottom_z").get<double>(), 1.05, 1e-9);
  EXPECT_NEAR(project.at("section").at("slice").at("thickness").get<double>(), 0.1, 1e-12);
  const json& planes = project.at("section").at("planes");
  ASSERT_EQ(planes.size(), 1u) << "the clip plane at the selected wall";
  EXPECT_NEAR(vector3(planes[0].at("normal")).y(), -1.0, 0.01) << "keeping the room's side, where the view is";
  EXPECT_NEAR(vector3(planes[0].at("point")).y(), 5.0, 0.01);
}

// The clip box's handles dragged in the view: a face moved in (the opposite face stays), the
// box moved by its centre, then turned a quarter about the vertical; the project keeps the box.
TEST(Viewer, TheClipBoxFollowsItsHandles) {
  const plumb::test::TempDirectory dir;
  const fs::path ply = dir.file("room.ply");
  const std::string simulate = std::string("'") + PLUMB_BINARY + "' simulate --scene room --points 200000 " +
                               "--noise-mm 2 -o '" + ply.string() + "' >/dev/null";
  ASSERT_EQ(std::system(simulate.c_str()), 0);
  // The box about the room (7 x 5 x 2.5 m), half a metre beyond each wall: x from -0.5 to 7.5.
  const json steps = json::array({
      {{"wait", "streaming_idle"}, {"timeout_s", 300}},
      // The x+ face from 7.5 to 5.0: the box spans x -0.5 to 5, its centre at 2.25.
      {{"drag_world", json::array({world({7.5, 2.5, 1.25}), world({5.0, 2.5, 1.25})})}},
      {{"wait", "frames"}, {"count", 2}},
      // The centre 0.5 m along x.
      {{"drag_world", json::array({world({2.25, 2.5, 1.25}), world({2.75, 2.5, 1.25})})}},
      {{"wait", "frames"}, {"count", 2}},
      // The turn handle (beyond the top of the x+ face: 2.75 + 2.75 + 0.75 m) a quarter turn about
      // the centre.
      {{"drag_world", json::array({world({6.25, 2.5, 2.75}), world({2.75, 6.0, 2.75})})}},
      {{"wait", "streaming_idle"}, {"timeout_s", 300}},
      {{"screenshot", "clip-box.png"}},
      {{"key_down", "LEFT_CONTROL"}},
      {{"key", "S"}},
      {{"key_up", "LEFT_CONTROL"}},
  });
  std::string arguments = "'";
  arguments += ply.string();
  arguments += "' --clip-box 3.5,2.5,1.25,8,6,3";
  ASSERT_EQ(plumb::test::runViewerSession(dir, arguments, steps, 1280, 720), 0);
  plumb::test::keepScreenshots(dir);
  const json box = readJson(ply.string() + ".plumbproj").at("section").at("box");
  std::printf("the box: %s\n", box.dump().c_str());
  // Dragged between pixels: each end lies within a few millimetres of the world point aimed at.
  EXPECT_NEAR((vector3(box.at("centre")) - Eigen::Vector3d(2.75, 2.5, 1.25)).norm(), 0.0, 0.02);
  EXPECT_NEAR((vector3(box.at("size")) - Eigen::Vector3d(5.5, 6.0, 3.0)).norm(), 0.0, 0.02);
  EXPECT_NEAR(box.at("turn_rad").get<double>(), M_PI / 2.0, 0.01);
  EXPECT_FALSE(box.at("keep_outside").get<bool>());
}

}  // namespace

namespace {

// A big point file shows a preview (every k-th point) while the whole file is imported; the
// whole cloud then takes its place, the view where the user took it, and the wait for
// streaming waits for it.
TEST(Viewer, ABigPointFileShowsAPreviewWhileItIsImported) {
  const plumb::test::TempDirectory dir;
  const std::string ply = dir.file("room.ply");
  const std::string simulate = std::string("'") + PLUMB_BINARY +
                               "' simulate --scene room --points 1100000 --noise-mm 2 -o '" + ply + "' >/dev/null";
  ASSERT_EQ(std::system(simulate.c_str()), 0);
  const json steps = json::array({{{"wait", "streaming_idle"}, {"timeout_s", 300}}, {{"screenshot", "whole.png"}}});
  ASSERT_EQ(plumb::test::runViewerSession(dir, "'" + ply + "'", steps, 1280, 720), 0);
  const std::string log = plumb::test::viewerLog(dir);
  std::printf("%s", log.c_str());
  const std::size_t preview = log.find("a preview while the whole file is imported");
  const std::size_t whole = log.find("now the whole cloud:");
  ASSERT_NE(preview, std::string::npos) << "no preview was shown";
  ASSERT_NE(whole, std::string::npos) << "the whole cloud did not replace the preview";
  EXPECT_LT(preview, whole);
  const std::uint64_t points = std::stoull(log.substr(whole + std::string("now the whole cloud: ").size()));
  EXPECT_GT(points, 1'050'000u) << "every point of the file, after the preview";
  plumb::test::keepScreenshots(dir);
}

}  // namespace
