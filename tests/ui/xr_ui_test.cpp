// The viewer in a headset, end to end, with no headset: `plumb view --xr` under Xvfb, on
// lavapipe with validation on, its OpenXR runtime the simulated headset of tests/support/xr_headset
// (loaded by Khronos' loader through XR_RUNTIME_JSON), which plays a script of head and controller
// poses and writes every eye image it is given to PNG.
//
// The room of the simulator (7 x 5 x 2.5 m): the user stands in its middle facing the x+ wall,
// a 30 cm square drawn 10 cm in front of that wall (a project's polygon); the right controller
// points at the wall and pulls the trigger, first while the session is not focused (nothing may
// happen), then focused: the wall grows. Both eyes show it, and the square's shift between the
// eyes is the one their poses and frusta imply.
//
// PLUMB_TEST_SCREENSHOTS=DIR keeps the eye images there for a person to look at.

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "engine/io/png_image.h"
#include "engine/view/camera.h"
#include "engine/view/camera_controls.h"
#include "tests/support/temp_directory.h"
#include "tests/ui/viewer_session.h"
#include "ui/xr/hand_panel.h"
#include "ui/xr/stage.h"

namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using plumb::test::jsonPoint;
using plumb::test::readJson;
using plumb::test::vector3;

const Eigen::Vector3d kOffset(512000.0, 5403000.0, 250.0);                  // the room's corner, UTM-like
const Eigen::Vector3d kStandAt = kOffset + Eigen::Vector3d(3.5, 2.5, 1.6);  // the eyes, facing +x
const Eigen::Vector3d kSquareCentre = kOffset + Eigen::Vector3d(6.9, 2.5, 1.7);
constexpr double kSquareHalf = 0.15;
constexpr int kEyeWidth = 480, kEyeHeight = 360;

// The room, simulated once for every test of this file.
class Headset : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    room_ = new plumb::test::TempDirectory("plumb_Headset_room");
    const std::string simulate = std::string("'") + PLUMB_BINARY +
                                 "' simulate --scene room --points 200000 --noise-mm 2 --seed 3 "
                                 "--offset 512000,5403000,250 -o '" +
                                 room_->file("room.ply") + "' >/dev/null && '" + PLUMB_BINARY + "' import '" +
                                 room_->file("room.ply") + "' -o '" + room_->file("room.plumb") + "' >/dev/null";
    ASSERT_EQ(std::system(simulate.c_str()), 0);
  }
  static void TearDownTestSuite() {
    delete room_;
    room_ = nullptr;
  }

  // The desktop's view (where the headset's stage is placed) and a project with the square.
  static std::string viewAndProject(const plumb::test::TempDirectory& dir) {
    std::ofstream(dir.file("camera.json")) << json{
        {"format", "plumb-camera"},
        {"version", 1},
        {"position", jsonPoint(kStandAt)},
        {"target", jsonPoint(kStandAt + Eigen::Vector3d(3.0, 0.0, 0.0))},
        {"fov_deg", 70},
        {"viewport", {1280, 720}}}.dump();
    json square = json::array();
    for (const auto& [dy, dz] : {std::pair{-1, -1}, {1, -1}, {1, 1}, {-1, 1}}) {
      square.push_back(jsonPoint(kSquareCentre + kSquareHalf * Eigen::Vector3d(0.0, dy, dz)));
    }
    std::ofstream(dir.file("room.plumbproj")) << json{
        {"format", "plumb-project"},
        {"version", 2},
        {"cloud", room_->file("room.plumb")},
        {"polygons",
         {{{"id", 1},
           {"name", "marker"},
           {"group", 0},
           {"plane", 0},
           {"vertices", square},
           {"extrusion", {0.0, 0.0, 0.0}}}}}}.dump();
    // Built by appending: GCC 12 -O3 warns (-Wrestrict) on "'" + std::string.
    std::string arguments = "'";
    arguments += room_->file("room.plumb");
    arguments += "' --xr --xr-resolution 1 --project '";
    arguments += dir.file("room.plumbproj");
    arguments += "' --camera '";
    arguments += dir.file("camera.json");
    arguments += "'";
    return arguments;
  }

  static std::string headsetEnvironment(const plumb::test::TempDirectory& dir, const json& script) {
    std::ofstream(dir.file("headset.json")) << script.dump(1);
    fs::create_directories(dir.file("eyes"));
    return std::string("XR_RUNTIME_JSON='") + PLUMB_XR_HEADSET_MANIFEST + "' PLUMB_XR_HEADSET_SCRIPT='" +
           dir.file("headset.json") + "' PLUMB_XR_HEADSET_OUT='" + dir.file("eyes") + "'";
  }

  static plumb::test::TempDirectory* room_;
};

plumb::test::TempDirectory* Headset::room_ = nullptr;

// The user's head in every script: standing, 1.6 m up, looking down the stage's -z.
const json kStanding = {{"position", {0, 1.6, 0}}, {"orientation", {0, 0, 0, 1}}};

// A session the runtime ends after 8 frames of the standing head, with small eyes.
json eightFramesThenExit() {
  return {{"eye_size", {160, 120}},
          {"capture", "none"},
          {"after_last_frame", "exit"},
          {"frames", {{{"repeat", 8}, {"head", kStanding}}}}};
}

json pose(const Eigen::Vector3d& position, const Eigen::Vector3d& look_at) {
  return {{"position", jsonPoint(position)}, {"look_at", jsonPoint(look_at)}};
}

// The horizontal centre of the square's white rim in an eye's image; nothing when absent.
std::optional<double> rimCentreX(const plumb::io::RgbaImage& image) {
  double sum = 0.0;
  std::size_t count = 0;
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      const std::uint32_t p = image.pixel(x, y);
      if ((p & 0xFFu) >= 250 && (p >> 8 & 0xFFu) >= 250 && (p >> 16 & 0xFFu) >= 250) {
        sum += x + 0.5;
        ++count;
      }
    }
  }
  if (count < 20) return std::nullopt;
  return sum / static_cast<double>(count);
}

// A Portable Float Map as the simulated headset writes depth: "Pf", width, height, a negative
// scale (little-endian), then rows bottom to top. Returned rows top to bottom.
struct DepthImage {
  int width = 0, height = 0;
  std::vector<float> depth;
  float at(int x, int y) const {
    return depth[static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x)];
  }
};

DepthImage readPfm(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::string magic;
  double scale = 0.0;
  DepthImage image;
  in >> magic >> image.width >> image.height >> scale;
  in.get();  // the one whitespace before the data
  EXPECT_EQ(magic, "Pf") << path;
  EXPECT_LT(scale, 0.0) << path;
  image.depth.resize(static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height));
  for (int row = image.height - 1; row >= 0; --row) {
    in.read(reinterpret_cast<char*>(image.depth.data() +
                                    static_cast<std::size_t>(row) * static_cast<std::size_t>(image.width)),
            static_cast<std::streamsize>(static_cast<std::size_t>(image.width) * sizeof(float)));
  }
  EXPECT_TRUE(in) << path << ": truncated";
  return image;
}

plumb::xr::Pose poseFromJson(const json& value) {
  plumb::xr::Pose pose;
  pose.position = vector3(value.at("position"));
  const json& q = value.at("orientation");
  pose.orientation = Eigen::Quaterniond(q[3].get<double>(), q[0].get<double>(), q[1].get<double>(), q[2].get<double>());
  return pose;
}

double differingShare(const plumb::io::RgbaImage& a, const plumb::io::RgbaImage& b) {
  std::size_t differing = 0;
  for (int y = 0; y < a.height; ++y) {
    for (int x = 0; x < a.width; ++x) differing += a.pixel(x, y) != b.pixel(x, y);
  }
  return static_cast<double>(differing) / (static_cast<double>(a.width) * a.height);
}

TEST_F(Headset, TheTriggerGrowsTheWallItPointsAtAndBothEyesShowIt) {
  const plumb::test::TempDirectory dir;
  // The stage: the head at 1.6 m looking down -z; -z is the desktop view's +x here, and the
  // stage's +x the world's -y. The controller, at the right hip, points at the wall 30 cm
  // right of and 50 cm below the square.
  const Eigen::Vector3d head(0.0, 1.6, 0.0);
  const json right = {{"aim", pose({0.2, 1.2, -0.3}, {0.3, 1.2, -3.5})}, {"trigger", 0.0}};
  json pulled = right;
  pulled["trigger"] = 1.0;
  const json script = {
      {"refresh_hz", 90},
      {"eye_size", {kEyeWidth, kEyeHeight}},
      {"ipd_m", 0.064},
      {"fov_deg", {{"left", -45}, {"right", 40}, {"up", 38}, {"down", -42}}},
      {"capture", {12}},
      {"capture_latest", true},
      {"after_last_frame", "hold"},
      {"frames",
       {{{"repeat", 10}, {"head", kStanding}, {"right", right}},
        {{"repeat", 5}, {"event", "unfocus"}, {"right", pulled}},  // not focused: no input reaches Plumb
        {{"repeat", 5}, {"event", "focus"}, {"right", right}},
        {{"repeat", 5}, {"right", pulled}},
        {{"repeat", 10}, {"right", right}}}}};
  const json steps = json::array({
      {{"tool", "grow"}},
      {{"wait", "frames"}, {"count", 40}},
      {{"wait", "grower_idle"}, {"timeout_s", 300}},
      {{"wait", "streaming_idle"}, {"timeout_s", 300}},
      {{"wait", "frames"}, {"count", 3}},
      {{"screenshot", "mirror.png"}},
  });
  ASSERT_EQ(plumb::test::runViewerSession(dir, viewAndProject(dir), steps, 1280, 720, headsetEnvironment(dir, script)),
            0);
  const std::string log = plumb::test::viewerLog(dir);
  EXPECT_NE(log.find("headset session focused"), std::string::npos) << log;

  // One grow, from the focused pull, on the x+ wall.
  const json dump = readJson(dir.file("scene.json"));
  std::size_t on_wall = 0;
  for (const json& segment : dump.at("segments")) {
    const Eigen::Vector3d normal = vector3(segment.at("normal"));
    const Eigen::Vector3d centroid = vector3(segment.at("centroid"));
    if (std::abs(normal.x()) > 0.999 && std::abs(centroid.x() - (kOffset.x() + 7.0)) < 0.01) ++on_wall;
  }
  EXPECT_EQ(on_wall, 1u) << dump.dump(1);
  EXPECT_EQ(std::count(log.begin(), log.end(), '\n') > 0 ? log.find("the controller grows at") : std::string::npos,
            log.rfind("the controller grows at"))
      << "one pull, one grow (the unfocused pull must do nothing)\n"
      << log;

  // Both eyes changed where the wall grew: before the pull (frame 12) and at the end.
  const std::array<std::string, 2> before{dir.file("eyes/frame-0012-eye-0.png"), dir.file("eyes/frame-0012-eye-1.png")};
  const std::array<std::string, 2> after{dir.file("eyes/latest-eye-0.png"), dir.file("eyes/latest-eye-1.png")};
  std::array<plumb::io::RgbaImage, 2> last;
  for (std::size_t eye = 0; eye < 2; ++eye) {
    const plumb::io::RgbaImage first = plumb::io::readPng(before[eye]);
    last[eye] = plumb::io::readPng(after[eye]);
    ASSERT_EQ(last[eye].width, kEyeWidth);
    ASSERT_EQ(last[eye].height, kEyeHeight);
    EXPECT_GT(differingShare(first, last[eye]), 0.05) << "eye " << eye << ": the grown wall does not show";
  }

  // The square's shift between the eyes, against its projection by each eye's camera: the
  // stage placed where the desktop camera was, the eyes where the runtime located them for the
  // last frame (frames.jsonl), each with its own off-axis frustum.
  std::ifstream frames(dir.file("eyes/frames.jsonl"));
  std::string line, last_line;
  while (std::getline(frames, line)) {
    if (!line.empty()) last_line = line;
  }
  const json views = json::parse(last_line).at("views");
  ASSERT_EQ(views.size(), 2u);
  // Each eye came with its depth (XR_KHR_composition_layer_depth), for the runtime's reprojection.
  EXPECT_TRUE(views[0].at("depth").get<bool>() && views[1].at("depth").get<bool>()) << last_line;
  plumb::view::Camera desktop;
  desktop.position = kStandAt;
  desktop.target = kStandAt + Eigen::Vector3d(3.0, 0.0, 0.0);
  plumb::xr::Pose head_pose;
  head_pose.position = head;
  const plumb::xr::StagePlacement stage = plumb::xr::placementAt(desktop, head_pose);
  std::array<double, 2> expected_x{}, measured_x{};
  for (std::size_t eye = 0; eye < 2; ++eye) {
    const json& fov = views[eye].at("fov");
    const plumb::view::Camera camera =
        plumb::xr::eyeCamera(stage, poseFromJson(views[eye].at("pose")),
                             {fov.at("left").get<double>(), fov.at("right").get<double>(), fov.at("up").get<double>(),
                              fov.at("down").get<double>()},
                             kEyeWidth, kEyeHeight);
    const std::optional<Eigen::Vector2d> pixel = plumb::view::pixelOf(camera, kSquareCentre);
    ASSERT_TRUE(pixel);
    expected_x[eye] = pixel->x();
    const std::optional<double> rim = rimCentreX(last[eye]);
    ASSERT_TRUE(rim) << "eye " << eye << ": the square's rim is not in the image";
    measured_x[eye] = *rim;
  }
  // The left eye's depth where the square is: the wall behind it (the depth is the cloud's; the
  // square is an overlay), 3.5 m from the eye along its view, as the layer's planes decode it.
  {
    const DepthImage depth = readPfm(dir.file("eyes/latest-depth-0.pfm"));
    ASSERT_EQ(depth.width, kEyeWidth);
    const json range = views[0].at("depth_range");
    const double near = range[0].get<double>(), far = range[1].get<double>();
    const plumb::view::Camera left =
        plumb::xr::eyeCamera(stage, poseFromJson(views[0].at("pose")),
                             {views[0]["fov"]["left"].get<double>(), views[0]["fov"]["right"].get<double>(),
                              views[0]["fov"]["up"].get<double>(), views[0]["fov"]["down"].get<double>()},
                             kEyeWidth, kEyeHeight);
    const Eigen::Vector2d pixel = *plumb::view::pixelOf(left, kSquareCentre);
    const double z = depth.at(static_cast<int>(pixel.x()), static_cast<int>(pixel.y()));
    const double view_depth = near * far / (far - z * (far - near));
    std::printf("the left eye's depth at the square: %.4f (%.4f m; planes %.3f, %.0f m)\n", z, view_depth, near, far);
    EXPECT_NEAR(view_depth, 3.5, 0.02);
  }
  const double expected = expected_x[0] - expected_x[1], measured = measured_x[0] - measured_x[1];
  std::printf("disparity of the square: expected %.2f px, measured %.2f px (left %.2f / %.2f, right %.2f / %.2f)\n",
              expected, measured, expected_x[0], measured_x[0], expected_x[1], measured_x[1]);
  EXPECT_GT(expected, 3.0) << "the test's geometry should give a visible disparity";
  EXPECT_NEAR(measured, expected, 1.0);
  EXPECT_NEAR(measured_x[0], expected_x[0], 1.5) << "the left eye's square is not where its camera puts it";

  if (const char* keep = std::getenv("PLUMB_TEST_SCREENSHOTS")) {
    fs::create_directories(keep);
    for (std::size_t eye = 0; eye < 2; ++eye) {
      fs::copy_file(after[eye], fs::path(keep) / ("xr-eye-" + std::to_string(eye) + ".png"),
                    fs::copy_options::overwrite_existing);
    }
  }
  plumb::test::keepScreenshots(dir);
}

// The pixel sizes the viewer reports for the controller's grows, in order.
std::vector<double> grownPixelsMm(const std::string& log) {
  std::vector<double> pixels;
  std::istringstream lines(log);
  std::string line;
  const std::string said = "a pixel ";
  while (std::getline(lines, line)) {
    if (line.find("the controller grows at") == std::string::npos) continue;
    const std::size_t at = line.find(said);
    if (at != std::string::npos) pixels.push_back(std::stod(line.substr(at + said.size())));
  }
  return pixels;
}

// Scale sets a click's detail as zoom does on the desktop: the same wall, pointed at from where
// the user stands, from 0.75 m nearer after walking with the thumbstick, and in the model on a
// table (B), grows with a pixel the size the left eye sees there.
TEST_F(Headset, WalkingNearerGrowsFinerAndTheModelOnATableCoarser) {
  const plumb::test::TempDirectory dir;
  const json aim = pose({0.2, 1.2, -0.3}, {0.0, 1.2, -3.5});
  const json still = {{"aim", aim}, {"trigger", 0.0}, {"thumbstick", {0.0, 0.0}}, {"b", false}};
  json pulled = still, walking = still, b_pressed = still;
  pulled["trigger"] = 1.0;
  walking["thumbstick"] = {0.0, 1.0};
  b_pressed["b"] = true;
  const json left_walking = {{"thumbstick", {0.0, 1.0}}};
  const json left_still = {{"thumbstick", {0.0, 0.0}}};
  const json script = {{"eye_size", {kEyeWidth, kEyeHeight}},
                       {"fov_deg", {{"left", -45}, {"right", 40}, {"up", 38}, {"down", -42}}},
                       {"capture", "none"},
                       {"after_last_frame", "hold"},
                       {"frames",
                        {{{"repeat", 10}, {"head", kStanding}, {"right", still}, {"left", left_still}},
                         {{"repeat", 5}, {"right", pulled}},
                         {{"repeat", 10}, {"right", still}},
                         {{"repeat", 45}, {"left", left_walking}},  // 45 frames at 90 Hz, full stick: 0.75 m
                         {{"repeat", 10}, {"left", left_still}},
                         {{"repeat", 5}, {"right", pulled}},
                         {{"repeat", 10}, {"right", still}},
                         {{"repeat", 5}, {"right", b_pressed}},  // the model on a table
                         {{"repeat", 10}, {"right", still}},
                         {{"repeat", 5}, {"right", pulled}},
                         {{"repeat", 10}, {"right", still}}}}};
  const json steps = json::array({
      {{"tool", "grow"}},
      {{"wait", "streaming_idle"}, {"timeout_s", 300}},
      {{"wait", "frames"}, {"count", 140}},
      {{"wait", "grower_idle"}, {"timeout_s", 300}},
  });
  ASSERT_EQ(plumb::test::runViewerSession(dir, viewAndProject(dir), steps, 640, 400, headsetEnvironment(dir, script)),
            0);
  const std::string log = plumb::test::viewerLog(dir);
  const std::vector<double> pixels = grownPixelsMm(log);
  ASSERT_EQ(pixels.size(), 3u) << log;
  std::printf("a pixel at the grows: %.2f mm (1:1), %.2f mm (0.75 m nearer), %.2f mm (the model)\n", pixels[0],
              pixels[1], pixels[2]);
  // The left eye 3.5 m from the wall, then 2.75 m; a pixel's size follows the depth.
  EXPECT_NEAR(pixels[1] / pixels[0], 2.75 / 3.5, 0.02) << log;
  // The model: the room 7 m long on 60 cm of table, its wall 0.8 m (stage) from the eyes.
  EXPECT_GT(pixels[2], 2.0 * pixels[0]) << log;
}

// The palette in the left hand: the right controller picks Measure on it, then measures the
// wall between two points 60 cm apart, a pull at each, as the mouse would on the desktop.
TEST_F(Headset, ThePaletteInTheLeftHandPicksATool) {
  const plumb::test::TempDirectory dir;
  constexpr int kWindowWidth = 1280, kWindowHeight = 720;
  plumb::xr::Pose left_hand;
  left_hand.position = {-0.15, 1.25, -0.35};  // held up, pointing forward (identity: down -z)
  const plumb::xr::HandPanel panel =
      plumb::xr::panelOnHand(left_hand, static_cast<double>(kWindowWidth) / kWindowHeight);
  // The Tools panel's Measure entry, at this window pixel of the palette (its layout is fixed).
  const Eigen::Vector2d measure_px(65.0, 92.0);
  const Eigen::Vector3d on_panel =
      panel.pose.position +
      panel.pose.orientation * Eigen::Vector3d((measure_px.x() / kWindowWidth - 0.5) * panel.width_m,
                                               (0.5 - measure_px.y() / kWindowHeight) * panel.height_m, 0.0);
  const Eigen::Vector3d right_hand(0.2, 1.3, -0.1);
  const json left = {{"aim", pose(left_hand.position, left_hand.position + Eigen::Vector3d(0.0, 0.0, -1.0))}};
  const auto right = [&](const Eigen::Vector3d& at, double trigger) {
    return json{{"aim", pose(right_hand, at)}, {"trigger", trigger}};
  };
  const Eigen::Vector3d point_a(0.3, 1.2, -3.5), point_b(-0.3, 1.2, -3.5);  // on the wall, 0.6 m apart
  const json script = {{"eye_size", {320, 240}},
                       {"capture", {30}},
                       {"after_last_frame", "hold"},
                       {"frames",
                        {{{"repeat", 20}, {"head", kStanding}, {"left", left}, {"right", right(on_panel, 0.0)}},
                         {{"repeat", 5}, {"right", right(on_panel, 1.0)}},
                         {{"repeat", 10}, {"right", right(on_panel, 0.0)}},
                         {{"repeat", 10}, {"right", right(point_a, 0.0)}},
                         {{"repeat", 5}, {"right", right(point_a, 1.0)}},
                         {{"repeat", 10}, {"right", right(point_a, 0.0)}},
                         {{"repeat", 10}, {"right", right(point_b, 0.0)}},
                         {{"repeat", 5}, {"right", right(point_b, 1.0)}},
                         {{"repeat", 10}, {"right", right(point_b, 0.0)}}}}};
  const json steps = json::array({
      {{"wait", "streaming_idle"}, {"timeout_s", 300}},
      {{"wait", "frames"}, {"count", 110}},
  });
  ASSERT_EQ(plumb::test::runViewerSession(dir, viewAndProject(dir), steps, kWindowWidth, kWindowHeight,
                                          headsetEnvironment(dir, script)),
            0);
  const std::string log = plumb::test::viewerLog(dir);
  EXPECT_EQ(log.find("the controller grows at"), std::string::npos) << "the panel's click reached the scene\n" << log;
  const json measurements = readJson(dir.file("scene.json")).at("measurements");
  ASSERT_EQ(measurements.size(), 1u) << measurements.dump(1) << "\n" << log;
  EXPECT_EQ(measurements[0].at("kind"), "distance");
  // Each end is the cloud's point nearest the ray (an exact point of the scan, as a mouse click
  // picks): within the room's point spacing, about 2.5 cm at 200,000 points, of where it aims.
  EXPECT_NEAR(measurements[0].at("value").get<double>(), 0.6, 0.05) << measurements.dump(1);
  // The panel went to the compositor as a quad over the eyes: the palette, not an empty image.
  const plumb::io::RgbaImage quad = plumb::io::readPng(dir.file("eyes/frame-0030-quad-0.png"));
  EXPECT_EQ(quad.width, kWindowWidth);
  std::size_t drawn = 0;
  for (int y = 0; y < quad.height; ++y) {
    for (int x = 0; x < quad.width; ++x) drawn += (quad.pixel(x, y) >> 24) != 0;
  }
  EXPECT_GT(static_cast<double>(drawn) / (quad.width * quad.height), 0.1) << "the palette is not on the panel";
  if (const char* keep = std::getenv("PLUMB_TEST_SCREENSHOTS")) {
    fs::create_directories(keep);
    fs::copy_file(dir.file("eyes/frame-0030-quad-0.png"), fs::path(keep) / "xr-panel.png",
                  fs::copy_options::overwrite_existing);
  }
}

// The controller snaps as the mouse does: in the Polygon tool's rectangle, three pulls each
// aimed 1 cm off a corner of the square make a rectangle whose corners are the square's, exactly.
TEST_F(Headset, TheControllersPullsSnapToTheSquaresCorners) {
  const plumb::test::TempDirectory dir;
  const Eigen::Vector3d right_hand(0.2, 1.3, -0.1);
  // The square's corner (dy, dz) in the stage (its -z is the world's +x, its +x the world's -y),
  // 1 cm off towards the square's inside.
  const auto nearCorner = [](int dy, int dz) {
    const Eigen::Vector3d world =
        kSquareCentre - kStandAt + Eigen::Vector3d(0.0, dy * (kSquareHalf - 0.01), dz * (kSquareHalf - 0.01));
    return Eigen::Vector3d(-world.y(), 1.6 + world.z(), -world.x());
  };
  const std::array<std::pair<int, int>, 3> corners{{{-1, -1}, {1, -1}, {1, 1}}};
  json frames = json::array({{{"repeat", 10},
                              {"head", kStanding},
                              {"right", {{"aim", pose(right_hand, nearCorner(-1, -1))}, {"trigger", 0.0}}}}});
  for (const auto& [dy, dz] : corners) {
    const json aim = pose(right_hand, nearCorner(dy, dz));
    frames.push_back({{"repeat", 10}, {"right", {{"aim", aim}, {"trigger", 0.0}}}});
    frames.push_back({{"repeat", 5}, {"right", {{"aim", aim}, {"trigger", 1.0}}}});
    frames.push_back({{"repeat", 5}, {"right", {{"aim", aim}, {"trigger", 0.0}}}});
  }
  const json script = {
      {"eye_size", {kEyeWidth, kEyeHeight}}, {"capture", "none"}, {"after_last_frame", "hold"}, {"frames", frames}};
  const json steps = json::array({
      {{"tool", "polygon"}},
      {{"key", "R"}},  // a rectangle from three points
      {{"wait", "streaming_idle"}, {"timeout_s", 300}},
      {{"wait", "frames"}, {"count", 90}},
  });
  ASSERT_EQ(plumb::test::runViewerSession(dir, viewAndProject(dir), steps, 640, 400, headsetEnvironment(dir, script)),
            0);
  const json polygons = readJson(dir.file("scene.json")).at("polygons");
  ASSERT_EQ(polygons.size(), 2u) << polygons.dump(1) << "\n" << plumb::test::viewerLog(dir);
  const json& drawn = polygons[1].at("vertices");
  ASSERT_EQ(drawn.size(), 4u) << polygons.dump(1);
  for (std::size_t i = 0; i < corners.size(); ++i) {
    const Eigen::Vector3d corner =
        kSquareCentre + kSquareHalf * Eigen::Vector3d(0.0, corners[i].first, corners[i].second);
    EXPECT_LT((vector3(drawn[i]) - corner).norm(), 1e-6) << "corner " << i << ": " << drawn.dump();
  }
}

// Direction finding with the controller: a polygon's first two vertices pulled at two corners
// of the square (A, then B above it), then the controller moved along the square's bottom edge
// into its corner D, which finds that edge's line; A held locks it, and a typed 0.5 puts the
// third vertex 0.5 m along it from B: level, where "towards the pointer" would have gone down
// to D.
//
//     B ------- C  ...  the third vertex, 0.5 m from B, level
//     |         |
//     A ------- D   <- the pointer moves along this edge into D
TEST_F(Headset, TheControllerFindsAndLocksADirection) {
  const plumb::test::TempDirectory dir;
  const Eigen::Vector3d right_hand(0.2, 1.3, -0.1);
  // A world point in the stage (its -z is the world's +x, its +x the world's -y).
  const auto stageOf = [](const Eigen::Vector3d& world) {
    const Eigen::Vector3d d = world - kStandAt;
    return Eigen::Vector3d(-d.y(), 1.6 + d.z(), -d.x());
  };
  const auto corner = [](int dy, int dz) {
    return Eigen::Vector3d(kSquareCentre + kSquareHalf * Eigen::Vector3d(0.0, dy, dz));
  };
  const Eigen::Vector3d a = corner(-1, -1), b = corner(-1, 1), d = corner(1, -1);
  const auto aimAt = [&](const Eigen::Vector3d& world, double trigger, bool lock = false) {
    return json{{"aim", pose(right_hand, stageOf(world))}, {"trigger", trigger}, {"a", lock}};
  };
  json frames = json::array({{{"repeat", 10}, {"head", kStanding}, {"right", aimAt(a, 0.0)}},
                             {{"repeat", 5}, {"right", aimAt(a, 1.0)}},
                             {{"repeat", 5}, {"right", aimAt(a, 0.0)}},
                             {{"repeat", 10}, {"right", aimAt(b, 0.0)}},
                             {{"repeat", 5}, {"right", aimAt(b, 1.0)}},
                             {{"repeat", 5}, {"right", aimAt(b, 0.0)}}});
  for (const double along : {-0.04, -0.03, -0.02, -0.01, 0.0}) {  // along the bottom edge, into D
    frames.push_back({{"repeat", 2}, {"right", aimAt(d + Eigen::Vector3d(0.0, along, 0.0), 0.0)}});
  }
  frames.push_back({{"repeat", 5}, {"right", aimAt(d, 0.0, true)}});
  const json script = {
      {"eye_size", {kEyeWidth, kEyeHeight}}, {"capture", "none"}, {"after_last_frame", "hold"}, {"frames", frames}};
  const json steps = json::array({
      {{"tool", "polygon"}},
      {{"wait", "streaming_idle"}, {"timeout_s", 300}},
      {{"wait", "frames"}, {"count", 100}},
      {{"type", "0.5"}},
      {{"key", "ENTER"}},  // the typed vertex
      {{"wait", "frames"}, {"count", 2}},
      {{"key", "ENTER"}},  // closes the polygon
      {{"wait", "frames"}, {"count", 2}},
  });
  ASSERT_EQ(plumb::test::runViewerSession(dir, viewAndProject(dir), steps, 640, 400, headsetEnvironment(dir, script)),
            0);
  const json polygons = readJson(dir.file("scene.json")).at("polygons");
  ASSERT_EQ(polygons.size(), 2u) << polygons.dump(1) << "\n" << plumb::test::viewerLog(dir);
  const json& drawn = polygons[1].at("vertices");
  ASSERT_EQ(drawn.size(), 3u) << polygons.dump(1);
  EXPECT_LT((vector3(drawn[0]) - a).norm(), 1e-6) << drawn.dump();
  EXPECT_LT((vector3(drawn[1]) - b).norm(), 1e-6) << drawn.dump();
  const Eigen::Vector3d step = vector3(drawn[2]) - b;
  EXPECT_NEAR(step.norm(), 0.5, 1e-6) << drawn.dump();
  EXPECT_NEAR(std::abs(step.y()), 0.5, 1e-6) << "not along the bottom edge's line: " << drawn.dump();
}

// The runtime ends the session (the user took the headset off and chose to leave): the viewer
// ends it cleanly and goes on on the desktop.
TEST_F(Headset, ASessionTheRuntimeEndsLeavesTheDesktopGoingOn) {
  const plumb::test::TempDirectory dir;
  const json script = eightFramesThenExit();
  const json steps = json::array({
      {{"wait", "streaming_idle"}, {"timeout_s", 300}},
      {{"wait", "frames"}, {"count", 30}},
      {{"screenshot", "desktop.png"}},
  });
  ASSERT_EQ(plumb::test::runViewerSession(dir, viewAndProject(dir), steps, 640, 400, headsetEnvironment(dir, script)),
            0);
  const std::string log = plumb::test::viewerLog(dir);
  for (const char* said :
       {"headset session on Plumb simulated headset", "headset session focused", "headset session stopping",
        "headset session exiting", "the headset session ended; the desktop goes on"}) {
    EXPECT_NE(log.find(said), std::string::npos) << said << "\n" << log;
  }
  EXPECT_TRUE(fs::exists(dir.file("shots/desktop.png")));
}

// A session ends and a new one starts from the palette's Enter VR: the runtime plays its script
// again, and ends that one too; the desktop goes on after each.
TEST_F(Headset, EnterVrStartsASessionAgainAfterOneEnded) {
  const plumb::test::TempDirectory dir;
  const json script = eightFramesThenExit();
  const json steps = json::array({
      {{"wait", "streaming_idle"}, {"timeout_s", 300}},
      {{"wait", "frames"}, {"count", 30}},
      {{"click", {915, 441}}},  // the View panel's Enter VR (its place in a 1280 x 720 window)
      {{"wait", "frames"}, {"count", 30}},
  });
  ASSERT_EQ(plumb::test::runViewerSession(dir, viewAndProject(dir), steps, 1280, 720, headsetEnvironment(dir, script)),
            0);
  const std::string log = plumb::test::viewerLog(dir);
  const auto count = [&](const std::string& said) {
    std::size_t n = 0;
    for (std::size_t at = log.find(said); at != std::string::npos; at = log.find(said, at + 1)) ++n;
    return n;
  };
  EXPECT_EQ(count("plumb view: headset session on "), 2u) << log;
  EXPECT_EQ(count("headset session focused"), 2u) << log;
  EXPECT_EQ(count("the headset session ended; the desktop goes on"), 2u) << log;
}

// No runtime: one message, and the desktop as usual.
TEST_F(Headset, WithoutARuntimeTheViewerSaysSoAndGoesOnOnTheDesktop) {
  const plumb::test::TempDirectory dir;
  const json steps = json::array({
      {{"wait", "streaming_idle"}, {"timeout_s", 300}},
      {{"screenshot", "desktop.png"}},
  });
  ASSERT_EQ(plumb::test::runViewerSession(dir, viewAndProject(dir), steps, 640, 400,
                                          "XR_RUNTIME_JSON='" + dir.file("no-such-runtime.json") + "'"),
            0);
  const std::string log = plumb::test::viewerLog(dir);
  EXPECT_NE(log.find("plumb view: no headset: no OpenXR runtime answered"), std::string::npos) << log;
  EXPECT_EQ(log.find("OpenXR-Loader"), std::string::npos) << "one message, not the loader's too\n" << log;
  EXPECT_TRUE(fs::exists(dir.file("shots/desktop.png")));
}

}  // namespace
