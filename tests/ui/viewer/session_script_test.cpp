// Session scripts: every step kind parses into the frames it replays; mistakes name the file
// and the step; the player waits for the grower and fails a wait that times out.

#include "ui/viewer/session_script.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <gtest/gtest.h>

#include <fstream>

#include "engine/core/error.h"
#include "engine/render/point_renderer.h"
#include "tests/support/temp_directory.h"

namespace plumb::viewer {
namespace {

std::string writeScript(const test::TempDirectory& dir, const std::string& text) {
  const std::string path = dir.file("session.json");
  std::ofstream(path) << text;
  return path;
}

std::string errorOf(const std::string& path) {
  try {
    readSessionScript(path);
  } catch (const Error& error) {
    return error.what();
  }
  return "";
}

TEST(SessionScript, ParsesEveryStepKind) {
  const test::TempDirectory dir;
  const std::vector<ScriptStep> steps = readSessionScript(writeScript(dir, R"([
    {"move": [10, 20]},
    {"click": [30, 40], "button": "right"},
    {"double_click": [5, 6]},
    {"click_world": [512000.5, 5403000.25, 251.0]},
    {"drag": [0, 0, 100, 50], "steps": 4},
    {"wheel": -2, "at": [7, 8]},
    {"key": "F", "hold_frames": 2},
    {"tool": "measure"},
    {"wait": "frames", "count": 3},
    {"wait": "ms", "ms": 5},
    {"wait": "grower_idle", "timeout_s": 9},
    {"wait": "streaming_idle"},
    {"screenshot": "a.png"},
    {"resize": [800, 600]},
    {"memory": "soak"},
    {"colour": "scan"},
    {"measure": "between_planes"},
    {"drag_world": [[1.0, 2.0, 3.0], [4.0, 5.0, 6.0]], "steps": 3}
  ])"));
  ASSERT_EQ(steps.size(), 18u);
  EXPECT_EQ(steps[0].frames.size(), 1u);
  ASSERT_EQ(steps[1].frames.size(), 3u) << "move, press, release: one frame each";
  EXPECT_EQ(steps[1].frames[1][0].button, GLFW_MOUSE_BUTTON_RIGHT);
  EXPECT_TRUE(steps[1].frames[1][0].pressed);
  EXPECT_FALSE(steps[1].frames[2][0].pressed);
  EXPECT_EQ(steps[2].frames.size(), 3u);
  EXPECT_EQ(steps[3].kind, ScriptStep::Kind::kClickWorld);
  EXPECT_DOUBLE_EQ(steps[3].world.y(), 5403000.25);
  EXPECT_EQ(steps[4].frames.size(), 2u + 4u + 1u) << "move, press, 4 moves, release";
  EXPECT_DOUBLE_EQ(steps[4].frames[3][0].x, 50.0);
  EXPECT_DOUBLE_EQ(steps[5].frames.back().back().wheel_y, -2.0);
  EXPECT_EQ(steps[6].frames.size(), 4u) << "press, two held frames, release";
  EXPECT_EQ(steps[6].frames.front()[0].key, GLFW_KEY_F);
  EXPECT_EQ(steps[7].tool, Tool::kMeasure);
  EXPECT_EQ(steps[8].count, 3u);
  EXPECT_DOUBLE_EQ(steps[9].ms, 5.0);
  EXPECT_DOUBLE_EQ(steps[10].timeout_s, 9.0);
  EXPECT_EQ(steps[11].kind, ScriptStep::Kind::kWaitStreamingIdle);
  EXPECT_EQ(steps[12].name, "a.png");
  EXPECT_EQ(steps[13].width, 800);
  EXPECT_EQ(steps[14].kind, ScriptStep::Kind::kMemory);
  EXPECT_EQ(steps[14].name, "soak");
  EXPECT_EQ(steps[15].kind, ScriptStep::Kind::kColour);
  EXPECT_EQ(steps[15].count, static_cast<std::uint64_t>(render::ColourMode::kScan));
  EXPECT_EQ(steps[16].kind, ScriptStep::Kind::kMeasure);
  EXPECT_EQ(steps[16].measure, cad::MeasureKind::kBetweenPlanes);
  EXPECT_EQ(steps[17].kind, ScriptStep::Kind::kDragWorld);
  EXPECT_EQ(steps[17].target, Eigen::Vector3d(4.0, 5.0, 6.0));
  EXPECT_EQ(steps[17].count, 3u);
}

TEST(SessionScript, MistakesNameTheFileAndTheStep) {
  const test::TempDirectory dir;
  EXPECT_NE(errorOf(writeScript(dir, "[{\"move\": [1, 2]}, {\"jump\": 1}]")).find("session.json: step 2: unknown step"),
            std::string::npos);
  EXPECT_NE(errorOf(writeScript(dir, "[{\"click\": [1]}]")).find("step 1: 'click' must be [x, y]"), std::string::npos);
  EXPECT_NE(errorOf(writeScript(dir, "[{\"key\": \"NOPE\"}]")).find("unknown key 'NOPE'"), std::string::npos);
  EXPECT_NE(errorOf(writeScript(dir, "[{\"wait\": \"forever\"}]")).find("unknown wait 'forever'"), std::string::npos);
  EXPECT_NE(errorOf(writeScript(dir, "[{\"colour\": \"pink\"}]")).find("unknown colour 'pink'"), std::string::npos);
  EXPECT_NE(errorOf(writeScript(dir, "[{\"measure\": \"volume\"}]")).find("unknown measure 'volume' (distance, angle"),
            std::string::npos);
  EXPECT_NE(
      errorOf(writeScript(dir, "[{\"drag_world\": [[1, 2, 3]]}]")).find("'drag_world' must be [[X, Y, Z], [X, Y, Z]]"),
      std::string::npos);
  EXPECT_NE(errorOf(writeScript(dir, "[{\"screenshot\": \"../x.png\"}]")).find("no folders"), std::string::npos);
  EXPECT_NE(errorOf(writeScript(dir, "[{\"click\": [1e300, 2]}]")).find("outside any window"), std::string::npos);
  EXPECT_NE(errorOf(writeScript(dir, "[{\"click_world\": [1, 2, \"z\"]}]")).find("[X, Y, Z]"), std::string::npos);
  EXPECT_NE(errorOf(writeScript(dir, "{\"move\": [1, 2]}")).find("expected a list of steps"), std::string::npos);
  EXPECT_NE(errorOf(writeScript(dir, "[{\"move\": [1, 2]")).find("not JSON"), std::string::npos);
  EXPECT_NE(errorOf(dir.file("missing.json")).find("cannot open"), std::string::npos);
}

TEST(SessionScript, ThePlayerReplaysFramesAndWaitsForTheGrower) {
  ScriptPlayer player(std::vector<ScriptStep>{
      ScriptStep{.kind = ScriptStep::Kind::kTool, .tool = Tool::kGrow},
      ScriptStep{.kind = ScriptStep::Kind::kEvents,
                 .frames = {{InputEvent{.kind = InputEvent::Kind::kMouseMove, .x = 1}},
                            {InputEvent{.kind = InputEvent::Kind::kMouseMove, .x = 2}}}},
      ScriptStep{.kind = ScriptStep::Kind::kWaitGrowerIdle},
      ScriptStep{.kind = ScriptStep::Kind::kScreenshot, .name = "done.png"},
  });
  ScriptFrame frame = player.next(true, true);
  EXPECT_EQ(frame.tool, Tool::kGrow) << "a tool step shares the next step's frame";
  ASSERT_EQ(frame.events.size(), 1u);
  EXPECT_DOUBLE_EQ(frame.events[0].x, 1.0);
  frame = player.next(true, true);
  EXPECT_DOUBLE_EQ(frame.events.at(0).x, 2.0);
  // The wait takes at least one frame, then lasts while the grower is busy.
  EXPECT_FALSE(player.next(true, true).screenshot);
  EXPECT_FALSE(player.next(false, true).screenshot);
  EXPECT_FALSE(player.next(false, true).screenshot);
  frame = player.next(true, true);
  EXPECT_EQ(frame.screenshot, "done.png");
  EXPECT_FALSE(frame.finished);
  EXPECT_TRUE(player.next(true, true).finished);
}

// On the script's clock a wait in milliseconds is a number of frames, however long they take:
// 250 ms are eight frames of 33.3 ms.
TEST(SessionScript, AWaitInMillisecondsCountsTheScriptsFrames) {
  ScriptPlayer player(std::vector<ScriptStep>{
      ScriptStep{.kind = ScriptStep::Kind::kWaitMs, .ms = 250.0},
      ScriptStep{.kind = ScriptStep::Kind::kScreenshot, .name = "after.png"},
  });
  for (int frame = 0; frame < 8; ++frame) EXPECT_FALSE(player.next(true, true).screenshot) << "frame " << frame;
  EXPECT_EQ(player.next(true, true).screenshot, "after.png");
}

// A last step that takes no frame of its own (a memory report, a colour mode) still runs before
// the session ends.
TEST(SessionScript, TheLastStepRunsBeforeTheSessionEnds) {
  ScriptPlayer player(std::vector<ScriptStep>{ScriptStep{.kind = ScriptStep::Kind::kMemory, .name = "end"}});
  const ScriptFrame frame = player.next(true, true);
  EXPECT_EQ(frame.memory, "end");
  EXPECT_FALSE(frame.finished);
  EXPECT_TRUE(player.next(true, true).finished);

  ScriptPlayer colour(std::vector<ScriptStep>{ScriptStep{.kind = ScriptStep::Kind::kColour, .count = 4}});
  EXPECT_EQ(colour.next(true, true).colour, 4);
  EXPECT_TRUE(colour.next(true, true).finished);
}

TEST(SessionScript, AWaitThatTimesOutFailsTheSession) {
  ScriptPlayer player(std::vector<ScriptStep>{
      ScriptStep{.kind = ScriptStep::Kind::kWaitStreamingIdle, .timeout_s = 0.0},
  });
  std::optional<std::string> failure;
  for (int i = 0; i < 100 && !failure; ++i) failure = player.next(true, false).failure;
  ASSERT_TRUE(failure);
  EXPECT_NE(failure->find("step 1: the wait timed out"), std::string::npos);
}

}  // namespace
}  // namespace plumb::viewer
