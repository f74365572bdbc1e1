// The simulated headset (tests/support/xr_headset) driven as an application drives a headset's
// runtime (test_application.h): Khronos' OpenXR loader finds it through XR_RUNTIME_JSON, the
// Vulkan instance and device are made through XR_KHR_vulkan_enable2 with the validation layer on
// (any message fails the test), and each test plays a small script written to its own folder.
// Images are 64 x 48 on lavapipe, a handful of frames each: the whole executable takes seconds.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "engine/io/png_image.h"
#include "tests/support/temp_directory.h"
#include "tests/support/xr_headset/test_application.h"

// Debian's OpenXR loader 1.0.20 leaks its per-instance bookkeeping (88 + 1216 bytes, allocated
// in xrCreateInstance, never freed by xrDestroyInstance; the same with a do-nothing stub runtime).
// LeakSanitizer reads these suppressions in sanitizer builds; elsewhere the function is unused.
extern "C" __attribute__((visibility("default"), used)) const char* __lsan_default_suppressions() {
  return "leak:libopenxr_loader.so\n";
}

namespace plumb::test {
namespace {

constexpr std::int64_t kPeriodNs = 11'111'111;  // 90 Hz, as the scripts say
constexpr double kIpdM = 0.064;
constexpr double kPoseTolerance = 1e-5;  // float poses against double expectations
constexpr int kColourTolerance = 1;      // UNORM conversion of the clear colours
constexpr double kPi = 3.14159265358979323846;

struct Vec3 {
  double x = 0, y = 0, z = 0;
};

Vec3 toVec3(const XrVector3f& v) {
  return {v.x, v.y, v.z};
}

// Rotates v by the unit quaternion q: v + 2w (u x v) + 2 u x (u x v).
Vec3 rotate(const XrQuaternionf& q, const Vec3& v) {
  const Vec3 u{q.x, q.y, q.z};
  const Vec3 t{2 * (u.y * v.z - u.z * v.y), 2 * (u.z * v.x - u.x * v.z), 2 * (u.x * v.y - u.y * v.x)};
  return {v.x + q.w * t.x + (u.y * t.z - u.z * t.y), v.y + q.w * t.y + (u.z * t.x - u.x * t.z),
          v.z + q.w * t.z + (u.x * t.y - u.y * t.x)};
}

void expectNear(const Vec3& actual, const Vec3& expected, double tolerance, const std::string& what) {
  EXPECT_NEAR(actual.x, expected.x, tolerance) << what;
  EXPECT_NEAR(actual.y, expected.y, tolerance) << what;
  EXPECT_NEAR(actual.z, expected.z, tolerance) << what;
}

// The fixture: the runtime's environment pointed at this test's folder, and the validation rule.
class SimulatedHeadset : public ::testing::Test {
 protected:
  void SetUp() override {
    keepCpuDriverLoaded();
    ::setenv("XR_RUNTIME_JSON", PLUMB_XR_HEADSET_MANIFEST, 1);
    ::setenv("PLUMB_XR_HEADSET_OUT", out().c_str(), 1);
    ::unsetenv("PLUMB_XR_HEADSET_SCRIPT");
  }

  void TearDown() override {
    app_.reset();
    for (const std::string& message : validation_messages_) ADD_FAILURE() << "Vulkan validation: " << message;
  }

  std::string out() const { return folder_.file("out"); }

  void useScript(const std::string& json) {
    ::setenv("PLUMB_XR_HEADSET_SCRIPT", folder_.write("script.json", json).c_str(), 1);
  }

  // An application with a running-ready session: instance, Vulkan, session, actions, swapchains.
  HeadsetApp& startApp(const AppOptions& options = {}) {
    app_ = std::make_unique<HeadsetApp>(&validation_messages_);
    app_->createInstance(options.depth);
    app_->queryGraphicsRequirements();
    app_->createVulkan();
    check(app_->tryCreateSession(), "xrCreateSession");
    app_->createSpacesAndActions();
    app_->createSwapchains(options);
    return *app_;
  }

  std::vector<nlohmann::json> frameLines() const {
    std::vector<nlohmann::json> lines;
    std::ifstream in(folder_.file("out/frames.jsonl"));
    for (std::string line; std::getline(in, line);) lines.push_back(nlohmann::json::parse(line));
    return lines;
  }

  TempDirectory folder_;
  std::vector<std::string> validation_messages_;
  std::unique_ptr<HeadsetApp> app_;
};

// Five frames: the head still, then turned to face -x elsewhere; the right trigger 0, 0.75, 0.25.
constexpr const char* kWalkScript = R"({
  "refresh_hz": 90,
  "eye_size": [64, 48],
  "ipd_m": 0.064,
  "fov_deg": {"left": -45, "right": 40, "up": 40, "down": -40},
  "capture": "all",
  "after_last_frame": "exit",
  "frames": [
    {"repeat": 2,
     "head": {"position": [0, 1.6, 0], "orientation": [0, 0, 0, 1]},
     "right": {"aim": {"position": [0.2, 1.4, -0.3], "look_at": [1.2, 1.4, -0.3]}, "trigger": 0.0}},
    {"repeat": 2, "head": {"position": [1, 1.5, 2], "look_at": [0, 1.5, 2]}, "right": {"trigger": 0.75}},
    {"right": {"trigger": 0.25}}
  ]
})";

constexpr std::size_t kWalkFrames = 5;

struct ScriptedHead {
  Vec3 position;
  XrQuaternionf orientation;
};

ScriptedHead walkHead(std::size_t frame) {
  const float half = static_cast<float>(std::sqrt(0.5));
  if (frame < 2) return {{0, 1.6, 0}, {0, 0, 0, 1}};
  return {{1, 1.5, 2}, {0, half, 0, half}};  // a quarter turn left: -z forward becomes -x
}

TEST_F(SimulatedHeadset, WritesEachEyeOfEachCapturedFrameAsAPng) {
  useScript(kWalkScript);
  const SessionSeen seen = startApp().run();
  ASSERT_EQ(seen.frames.size(), kWalkFrames);
  for (std::size_t frame = 0; frame < kWalkFrames; ++frame) {
    // The application's clear colours (test_application.h) as stored: BGRA swizzled back to RGBA.
    const auto green = static_cast<std::uint8_t>(std::lround(greenOfFrame(frame) * 255));
    const std::uint8_t expected[2][4] = {{0, 0, 255, 255}, {255, green, 0, 255}};
    for (int eye = 0; eye < 2; ++eye) {
      char name[64];
      std::snprintf(name, sizeof name, "out/frame-%04zu-eye-%d.png", frame, eye);
      const io::RgbaImage image = io::readPng(folder_.file(name));
      ASSERT_EQ(image.width, static_cast<int>(kEyeWidthPx)) << name;
      ASSERT_EQ(image.height, static_cast<int>(kEyeHeightPx)) << name;
      int worst = 0;
      for (std::size_t i = 0; i < image.rgba.size(); ++i) {
        worst = std::max(worst, std::abs(int{image.rgba[i]} - int{expected[eye][i % 4]}));
      }
      EXPECT_LE(worst, kColourTolerance) << name << ": the clear colour did not come back";
    }
  }
  EXPECT_FALSE(std::filesystem::exists(folder_.file("out/frame-0005-eye-0.png"))) << "a frame past the script";
}

TEST_F(SimulatedHeadset, RecordsEachSubmittedFrameInFramesJsonl) {
  useScript(kWalkScript);
  const SessionSeen seen = startApp().run();
  const std::vector<nlohmann::json> lines = frameLines();
  ASSERT_EQ(lines.size(), kWalkFrames);
  for (std::size_t frame = 0; frame < kWalkFrames; ++frame) {
    const nlohmann::json& line = lines[frame];
    EXPECT_EQ(line["frame"], frame);
    EXPECT_EQ(line["display_time"], static_cast<std::int64_t>(frame + 1) * kPeriodNs);
    EXPECT_EQ(line["layers"], 1);
    EXPECT_EQ(line["quads"], 0);
    ASSERT_EQ(line["views"].size(), 2u);
    for (std::size_t eye = 0; eye < 2; ++eye) {
      const nlohmann::json& view = line["views"][eye];
      const XrView& located = seen.frames[frame].views[eye];
      expectNear({view["pose"]["position"][0], view["pose"]["position"][1], view["pose"]["position"][2]},
                 toVec3(located.pose.position), kPoseTolerance, "the submitted view's position");
      EXPECT_NEAR(view["pose"]["orientation"][3].get<double>(), located.pose.orientation.w, kPoseTolerance);
      EXPECT_NEAR(view["fov"]["left"].get<double>(), located.fov.angleLeft, kPoseTolerance);
      EXPECT_NEAR(view["fov"]["up"].get<double>(), located.fov.angleUp, kPoseTolerance);
      EXPECT_EQ(view["image_rect"], nlohmann::json({0, 0, kEyeWidthPx, kEyeHeightPx}));
      EXPECT_EQ(view["depth"], false);
    }
  }
}

TEST_F(SimulatedHeadset, LocatesTheEyesIpdApartAtTheScriptedHead) {
  useScript(kWalkScript);
  const SessionSeen seen = startApp().run();
  ASSERT_EQ(seen.frames.size(), kWalkFrames);
  for (std::size_t frame = 0; frame < kWalkFrames; ++frame) {
    const FrameSeen& seen_frame = seen.frames[frame];
    const std::string where = "frame " + std::to_string(frame);
    EXPECT_EQ(seen_frame.display_time, static_cast<std::int64_t>(frame + 1) * kPeriodNs) << where;
    EXPECT_EQ(seen_frame.view_state.viewStateFlags & XR_VIEW_STATE_POSITION_TRACKED_BIT,
              XR_VIEW_STATE_POSITION_TRACKED_BIT);
    const ScriptedHead head = walkHead(frame);
    const Vec3 left = toVec3(seen_frame.views[0].pose.position), right = toVec3(seen_frame.views[1].pose.position);
    // The eyes straddle the head along its own +x axis, ipd apart.
    expectNear({(left.x + right.x) / 2, (left.y + right.y) / 2, (left.z + right.z) / 2}, head.position, kPoseTolerance,
               where + ": the eyes' midpoint");
    const Vec3 head_right = rotate(head.orientation, {1, 0, 0});
    expectNear({right.x - left.x, right.y - left.y, right.z - left.z},
               {head_right.x * kIpdM, head_right.y * kIpdM, head_right.z * kIpdM}, kPoseTolerance,
               where + ": left eye to right eye");
    for (const XrView& view : seen_frame.views) {
      const Vec3 forward = rotate(view.pose.orientation, {0, 0, -1});
      expectNear(forward, rotate(head.orientation, {0, 0, -1}), kPoseTolerance, where + ": the eye looks as the head");
    }
    // The script's field of view for the left eye, mirrored for the right.
    const XrFovf& left_fov = seen_frame.views[0].fov;
    const XrFovf& right_fov = seen_frame.views[1].fov;
    EXPECT_NEAR(left_fov.angleLeft, -45 * kPi / 180, kPoseTolerance);
    EXPECT_NEAR(left_fov.angleRight, 40 * kPi / 180, kPoseTolerance);
    EXPECT_NEAR(left_fov.angleUp, 40 * kPi / 180, kPoseTolerance);
    EXPECT_NEAR(left_fov.angleDown, -40 * kPi / 180, kPoseTolerance);
    EXPECT_NEAR(right_fov.angleLeft, -40 * kPi / 180, kPoseTolerance);
    EXPECT_NEAR(right_fov.angleRight, 45 * kPi / 180, kPoseTolerance);
  }
}

TEST_F(SimulatedHeadset, TriggerAndAimFollowTheScript) {
  useScript(kWalkScript);
  const SessionSeen seen = startApp().run();
  ASSERT_EQ(seen.frames.size(), kWalkFrames);
  const float triggers[kWalkFrames] = {0, 0, 0.75f, 0.75f, 0.25f};
  const bool changed[kWalkFrames] = {false, false, true, false, true};
  const std::size_t last_change[kWalkFrames] = {0, 0, 2, 2, 4};
  for (std::size_t frame = 0; frame < kWalkFrames; ++frame) {
    const FrameSeen& seen_frame = seen.frames[frame];
    const std::string where = "frame " + std::to_string(frame);
    EXPECT_EQ(seen_frame.sync_result, XR_SUCCESS) << where;
    EXPECT_TRUE(seen_frame.trigger.isActive) << where;
    EXPECT_FLOAT_EQ(seen_frame.trigger.currentState, triggers[frame]) << where;
    EXPECT_EQ(seen_frame.trigger.changedSinceLastSync, changed[frame] ? XR_TRUE : XR_FALSE) << where;
    EXPECT_EQ(seen_frame.trigger.lastChangeTime, static_cast<std::int64_t>(last_change[frame] + 1) * kPeriodNs)
        << where;
    EXPECT_TRUE(seen_frame.aim.isActive) << where;
    // The aim held at (0.2, 1.4, -0.3) pointing at +x.
    const XrSpaceLocation& aim = seen_frame.aim_location;
    EXPECT_EQ(aim.locationFlags & XR_SPACE_LOCATION_POSITION_VALID_BIT, XR_SPACE_LOCATION_POSITION_VALID_BIT) << where;
    expectNear(toVec3(aim.pose.position), {0.2, 1.4, -0.3}, kPoseTolerance, where + ": aim position");
    expectNear(rotate(aim.pose.orientation, {0, 0, -1}), {1, 0, 0}, kPoseTolerance, where + ": aim direction");
  }
}

TEST_F(SimulatedHeadset, SessionGoesFromReadyToExitingAtTheScriptsEnd) {
  useScript(kWalkScript);
  const SessionSeen seen = startApp().run();
  const std::vector<XrSessionState> expected{
      XR_SESSION_STATE_IDLE,    XR_SESSION_STATE_READY,   XR_SESSION_STATE_SYNCHRONIZED, XR_SESSION_STATE_VISIBLE,
      XR_SESSION_STATE_FOCUSED, XR_SESSION_STATE_VISIBLE, XR_SESSION_STATE_SYNCHRONIZED, XR_SESSION_STATE_STOPPING,
      XR_SESSION_STATE_IDLE,    XR_SESSION_STATE_EXITING};
  EXPECT_EQ(seen.states, expected);
  EXPECT_EQ(seen.frames.size(), kWalkFrames);
  for (const FrameSeen& frame : seen.frames) EXPECT_TRUE(frame.should_render);
}

TEST_F(SimulatedHeadset, UnfocusedFramesReadNoInput) {
  useScript(R"({"eye_size": [64, 48], "capture": "none", "frames": [
    {"right": {"trigger": 1}}, {"event": "unfocus"}, {"event": "focus"}]})");
  const SessionSeen seen = startApp().run();
  ASSERT_EQ(seen.frames.size(), 3u);
  EXPECT_TRUE(seen.frames[0].trigger.isActive);
  EXPECT_EQ(seen.frames[1].sync_result, XR_SESSION_NOT_FOCUSED);
  EXPECT_FALSE(seen.frames[1].trigger.isActive);
  EXPECT_TRUE(seen.frames[1].should_render) << "a visible session still renders";
  EXPECT_TRUE(seen.frames[2].trigger.isActive);
  EXPECT_FLOAT_EQ(seen.frames[2].trigger.currentState, 1);
  const std::vector<XrSessionState> expected{
      XR_SESSION_STATE_IDLE,     XR_SESSION_STATE_READY,   XR_SESSION_STATE_SYNCHRONIZED,
      XR_SESSION_STATE_VISIBLE,  XR_SESSION_STATE_FOCUSED, XR_SESSION_STATE_VISIBLE,
      XR_SESSION_STATE_FOCUSED,  XR_SESSION_STATE_VISIBLE, XR_SESSION_STATE_SYNCHRONIZED,
      XR_SESSION_STATE_STOPPING, XR_SESSION_STATE_IDLE,    XR_SESSION_STATE_EXITING};
  EXPECT_EQ(seen.states, expected);
  EXPECT_FALSE(std::filesystem::exists(folder_.file("out/frame-0000-eye-0.png"))) << "\"capture\": \"none\"";
}

TEST_F(SimulatedHeadset, OnlyTheScriptedProfilesBindingsAreActive) {
  // The application suggested touch controller bindings for the trigger and the aim; the user
  // holds simple controllers.
  useScript(R"({"eye_size": [64, 48], "capture": "none", "profile": "/interaction_profiles/khr/simple_controller",
                "frames": [{"right": {"trigger": 1}}]})");
  HeadsetApp& app = startApp();
  const SessionSeen seen = app.run();
  ASSERT_EQ(seen.frames.size(), 1u);
  EXPECT_EQ(seen.frames[0].sync_result, XR_SUCCESS);
  EXPECT_FALSE(seen.frames[0].trigger.isActive);
  EXPECT_FALSE(seen.frames[0].aim.isActive);
  EXPECT_EQ(seen.frames[0].aim_location.locationFlags, 0u) << "an inactive aim is not tracked";
  XrPath right_hand = XR_NULL_PATH, simple = XR_NULL_PATH;
  check(xrStringToPath(app.instance(), "/user/hand/right", &right_hand), "xrStringToPath");
  check(xrStringToPath(app.instance(), "/interaction_profiles/khr/simple_controller", &simple), "xrStringToPath");
  auto profile = xrStruct<XrInteractionProfileState>(XR_TYPE_INTERACTION_PROFILE_STATE);
  check(xrGetCurrentInteractionProfile(app.session(), right_hand, &profile), "xrGetCurrentInteractionProfile");
  EXPECT_EQ(profile.interactionProfile, simple);
}

TEST_F(SimulatedHeadset, LoseEventLosesTheSession) {
  useScript(R"({"eye_size": [64, 48], "capture": "none", "frames": [{}, {"event": "lose"}, {}]})");
  HeadsetApp& app = startApp();
  const SessionSeen seen = app.run();
  ASSERT_EQ(seen.frames.size(), 2u);
  EXPECT_EQ(seen.frames[1].wait_result, XR_SESSION_LOSS_PENDING);
  EXPECT_EQ(seen.states.back(), XR_SESSION_STATE_LOSS_PENDING);
  auto state = xrStruct<XrFrameState>(XR_TYPE_FRAME_STATE);
  EXPECT_EQ(xrWaitFrame(app.session(), nullptr, &state), XR_ERROR_SESSION_LOST);
}

TEST_F(SimulatedHeadset, RecordsDepthInfoAndQuadLayers) {
  useScript(R"({"eye_size": [64, 48], "frames": [{}]})");
  const SessionSeen seen = startApp({.depth = true, .quad = true}).run();
  ASSERT_EQ(seen.frames.size(), 1u);
  const std::vector<nlohmann::json> lines = frameLines();
  ASSERT_EQ(lines.size(), 1u);
  EXPECT_EQ(lines[0]["layers"], 2);
  EXPECT_EQ(lines[0]["quads"], 1);
  EXPECT_EQ(lines[0]["views"][0]["depth"], true);
  EXPECT_EQ(lines[0]["views"][1]["depth"], true);
  const io::RgbaImage quad = io::readPng(folder_.file("out/frame-0000-quad-0.png"));
  EXPECT_EQ(quad.width, 32);
  EXPECT_EQ(quad.height, 16);
  EXPECT_EQ(quad.pixel(5, 5), 0xff00ffffu) << "yellow, R in the lowest byte";
}

TEST_F(SimulatedHeadset, RefusesCallsOutOfOrder) {
  useScript(R"({"eye_size": [64, 48], "capture": "none", "after_last_frame": "hold", "frames": [{}]})");
  app_ = std::make_unique<HeadsetApp>(&validation_messages_);
  app_->createInstance(false);
  app_->createVulkan();
  EXPECT_EQ(app_->tryCreateSession(), XR_ERROR_GRAPHICS_REQUIREMENTS_CALL_MISSING);
  app_->queryGraphicsRequirements();
  check(app_->tryCreateSession(), "xrCreateSession");
  const XrSession session = app_->session();
  auto state = xrStruct<XrFrameState>(XR_TYPE_FRAME_STATE);
  EXPECT_EQ(xrWaitFrame(session, nullptr, &state), XR_ERROR_SESSION_NOT_RUNNING);
  auto begin = xrStruct<XrSessionBeginInfo>(XR_TYPE_SESSION_BEGIN_INFO);
  begin.primaryViewConfigurationType = XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO;
  check(xrBeginSession(session, &begin), "xrBeginSession");
  EXPECT_EQ(xrBeginSession(session, &begin), XR_ERROR_SESSION_RUNNING);
  EXPECT_EQ(xrBeginFrame(session, nullptr), XR_ERROR_CALL_ORDER_INVALID) << "no xrWaitFrame yet";
  check(xrWaitFrame(session, nullptr, &state), "xrWaitFrame");
  EXPECT_EQ(xrWaitFrame(session, nullptr, &state), XR_ERROR_CALL_ORDER_INVALID) << "waited twice";
  auto end = xrStruct<XrFrameEndInfo>(XR_TYPE_FRAME_END_INFO);
  end.displayTime = state.predictedDisplayTime;
  end.environmentBlendMode = XR_ENVIRONMENT_BLEND_MODE_OPAQUE;
  EXPECT_EQ(xrEndFrame(session, &end), XR_ERROR_CALL_ORDER_INVALID) << "not begun";
  EXPECT_EQ(xrBeginFrame(session, nullptr), XR_SUCCESS);
  check(xrWaitFrame(session, nullptr, &state), "xrWaitFrame");
  EXPECT_EQ(xrBeginFrame(session, nullptr), XR_FRAME_DISCARDED) << "the previous frame was never ended";
  EXPECT_EQ(xrEndSession(session), XR_ERROR_SESSION_NOT_STOPPING);
  EXPECT_EQ(xrRequestExitSession(session), XR_SUCCESS);

  auto info = xrStruct<XrSwapchainCreateInfo>(XR_TYPE_SWAPCHAIN_CREATE_INFO);
  info.usageFlags = XR_SWAPCHAIN_USAGE_COLOR_ATTACHMENT_BIT;
  info.format = VK_FORMAT_R8G8B8A8_UNORM;
  info.sampleCount = info.faceCount = info.arraySize = info.mipCount = 1;
  info.width = info.height = 8;
  XrSwapchain swapchain = XR_NULL_HANDLE;
  check(xrCreateSwapchain(session, &info, &swapchain), "xrCreateSwapchain");
  EXPECT_EQ(xrReleaseSwapchainImage(swapchain, nullptr), XR_ERROR_CALL_ORDER_INVALID) << "nothing acquired";
  std::uint32_t index = 0;
  for (int i = 0; i < 3; ++i) EXPECT_EQ(xrAcquireSwapchainImage(swapchain, nullptr, &index), XR_SUCCESS);
  EXPECT_EQ(xrAcquireSwapchainImage(swapchain, nullptr, &index), XR_ERROR_CALL_ORDER_INVALID) << "all 3 held";
  check(xrDestroySwapchain(swapchain), "xrDestroySwapchain");
  info.format = 12345;
  EXPECT_EQ(xrCreateSwapchain(session, &info, &swapchain), XR_ERROR_SWAPCHAIN_FORMAT_UNSUPPORTED);
}

TEST_F(SimulatedHeadset, DescribesItselfAndNamesThings) {
  useScript(R"({"eye_size": [64, 48]})");
  std::uint32_t count = 0;
  check(xrEnumerateInstanceExtensionProperties(nullptr, 0, &count, nullptr), "xrEnumerateInstanceExtensionProperties");
  std::vector<XrExtensionProperties> extensions(count, xrStruct<XrExtensionProperties>(XR_TYPE_EXTENSION_PROPERTIES));
  check(xrEnumerateInstanceExtensionProperties(nullptr, count, &count, extensions.data()),
        "xrEnumerateInstanceExtensionProperties");
  std::vector<std::string> names;
  for (const XrExtensionProperties& extension : extensions) names.emplace_back(extension.extensionName);
  EXPECT_NE(std::find(names.begin(), names.end(), XR_KHR_VULKAN_ENABLE2_EXTENSION_NAME), names.end());
  EXPECT_NE(std::find(names.begin(), names.end(), XR_KHR_COMPOSITION_LAYER_DEPTH_EXTENSION_NAME), names.end());

  app_ = std::make_unique<HeadsetApp>(&validation_messages_);
  app_->createInstance(false);
  const XrInstance instance = app_->instance();
  auto properties = xrStruct<XrInstanceProperties>(XR_TYPE_INSTANCE_PROPERTIES);
  check(xrGetInstanceProperties(instance, &properties), "xrGetInstanceProperties");
  EXPECT_STREQ(properties.runtimeName, "Plumb simulated headset");

  char text[XR_MAX_RESULT_STRING_SIZE];
  check(xrResultToString(instance, XR_ERROR_SESSION_LOST, text), "xrResultToString");
  EXPECT_STREQ(text, "XR_ERROR_SESSION_LOST");
  check(xrResultToString(instance, static_cast<XrResult>(-999), text), "xrResultToString");
  EXPECT_STREQ(text, "XR_UNKNOWN_FAILURE_-999");
  char type_name[XR_MAX_STRUCTURE_NAME_SIZE];
  check(xrStructureTypeToString(instance, XR_TYPE_FRAME_STATE, type_name), "xrStructureTypeToString");
  EXPECT_STREQ(type_name, "XR_TYPE_FRAME_STATE");

  XrPath path = XR_NULL_PATH;
  check(xrStringToPath(instance, "/user/hand/left/input/trigger/value", &path), "xrStringToPath");
  char path_text[XR_MAX_PATH_LENGTH];
  check(xrPathToString(instance, path, XR_MAX_PATH_LENGTH, &count, path_text), "xrPathToString");
  EXPECT_STREQ(path_text, "/user/hand/left/input/trigger/value");
  EXPECT_EQ(count, std::strlen(path_text) + 1);
  EXPECT_EQ(xrStringToPath(instance, "/user//hand", &path), XR_ERROR_PATH_FORMAT_INVALID);
  EXPECT_EQ(xrStringToPath(instance, "/User/hand", &path), XR_ERROR_PATH_FORMAT_INVALID);

  // The view configuration: two eyes of the script's size.
  auto system_info = xrStruct<XrSystemGetInfo>(XR_TYPE_SYSTEM_GET_INFO);
  system_info.formFactor = XR_FORM_FACTOR_HEAD_MOUNTED_DISPLAY;
  XrSystemId system = XR_NULL_SYSTEM_ID;
  check(xrGetSystem(instance, &system_info, &system), "xrGetSystem");
  XrViewConfigurationView views[2] = {xrStruct<XrViewConfigurationView>(XR_TYPE_VIEW_CONFIGURATION_VIEW),
                                      xrStruct<XrViewConfigurationView>(XR_TYPE_VIEW_CONFIGURATION_VIEW)};
  check(
      xrEnumerateViewConfigurationViews(instance, system, XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO, 2, &count, views),
      "xrEnumerateViewConfigurationViews");
  EXPECT_EQ(count, 2u);
  EXPECT_EQ(views[1].recommendedImageRectWidth, 64u);
  EXPECT_EQ(views[1].recommendedImageRectHeight, 48u);
  system_info.formFactor = XR_FORM_FACTOR_HANDHELD_DISPLAY;
  EXPECT_EQ(xrGetSystem(instance, &system_info, &system), XR_ERROR_FORM_FACTOR_UNSUPPORTED);
}

TEST_F(SimulatedHeadset, MissingRuntimeManifestFailsInstanceCreation) {
  ::setenv("XR_RUNTIME_JSON", folder_.file("no_such_manifest.json").c_str(), 1);
  auto create = xrStruct<XrInstanceCreateInfo>(XR_TYPE_INSTANCE_CREATE_INFO);
  std::snprintf(create.applicationInfo.applicationName, XR_MAX_APPLICATION_NAME_SIZE, "%s", "plumb_xr_headset_tests");
  create.applicationInfo.apiVersion = XR_CURRENT_API_VERSION;
  XrInstance instance = XR_NULL_HANDLE;
  EXPECT_TRUE(XR_FAILED(xrCreateInstance(&create, &instance)));
  EXPECT_EQ(instance, XR_NULL_HANDLE);
}

TEST_F(SimulatedHeadset, MalformedScriptFailsInstanceCreationNamingTheFileAndTheProblem) {
  useScript(R"({"frames": [{"head": {"position": [0, 1.6]}}]})");
  auto create = xrStruct<XrInstanceCreateInfo>(XR_TYPE_INSTANCE_CREATE_INFO);
  std::snprintf(create.applicationInfo.applicationName, XR_MAX_APPLICATION_NAME_SIZE, "%s", "plumb_xr_headset_tests");
  create.applicationInfo.apiVersion = XR_CURRENT_API_VERSION;
  const char* extensions[] = {XR_KHR_VULKAN_ENABLE2_EXTENSION_NAME};
  create.enabledExtensionCount = 1;
  create.enabledExtensionNames = extensions;
  XrInstance instance = XR_NULL_HANDLE;
  ::testing::internal::CaptureStderr();
  const XrResult result = xrCreateInstance(&create, &instance);
  const std::string printed = ::testing::internal::GetCapturedStderr();
  EXPECT_EQ(result, XR_ERROR_RUNTIME_FAILURE);
  EXPECT_NE(printed.find("simulated headset: "), std::string::npos) << printed;
  EXPECT_NE(printed.find(folder_.file("script.json")), std::string::npos) << printed;
  EXPECT_NE(printed.find("frames[0].head.position"), std::string::npos) << printed;
  if (instance != XR_NULL_HANDLE) xrDestroyInstance(instance);
}

}  // namespace
}  // namespace plumb::test
