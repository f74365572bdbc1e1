#pragma once
// Running `plumb view` under Xvfb as the ui tests do: on lavapipe with validation on (any message
// fails the run), replaying a scripted session (ui/viewer/session_script.h) from a temporary file.

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <string>

#include "tests/support/temp_directory.h"

namespace plumb::test {

inline nlohmann::json readJson(const std::filesystem::path& path) {
  std::ifstream in(path);
  return nlohmann::json::parse(in);
}

inline Eigen::Vector3d vector3(const nlohmann::json& value) {
  return {value[0].get<double>(), value[1].get<double>(), value[2].get<double>()};
}

inline nlohmann::json jsonPoint(const Eigen::Vector3d& p) {
  return nlohmann::json::array({p.x(), p.y(), p.z()});
}

// `xvfb-run -a`, which starts Xvfb on the first free display from 99 and waits for it to be ready.
// -noreset: a server that resets whenever its last client goes refuses connections while it does.
inline std::string xvfbRun(const std::string& screen) {
  return "xvfb-run -a -s '-screen 0 " + screen + " -noreset'";
}

// What the last session printed (stdout and stderr).
inline std::string viewerLog(const TempDirectory& dir) {
  std::ifstream in(dir.file("viewer.log"));
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// Runs `<environment> plumb view <arguments> --script <steps> --screenshot-dir <dir>/shots
// --dump-scene <dir>/scene.json` in a `width` x `height` window under Xvfb, its output into
// <dir>/viewer.log; returns the command's exit status (0: the script ran to its end without a
// validation message).
//
// A session whose viewer could not reach its X server is started again, up to three times: under
// load, a server xvfb-run has started and found ready now and then refuses the first client
// ("X11: Failed to open display :N" a second into the run, seen in CI about once in 400 sessions,
// on displays both reused and fresh). Such a session never ran, so running it again hides nothing
// the test is about.
inline int runViewerSession(const TempDirectory& dir, const std::string& arguments, const nlohmann::json& steps,
                            int width = 1920, int height = 1080, const std::string& environment = "") {
  const std::string script = dir.file("session.json");
  std::ofstream(script) << steps.dump(1);
  const std::string size = std::to_string(width) + "x" + std::to_string(height);
  const std::string command = environment + " PLUMB_VALIDATION=1 PLUMB_GPU=cpu " + xvfbRun(size + "x24") + " '" +
                              PLUMB_BINARY + "' view " + arguments + " --script '" + script + "' --screenshot-dir '" +
                              dir.file("shots") + "' --dump-scene '" + dir.file("scene.json") + "' --width " +
                              std::to_string(width) + " --height " + std::to_string(height) + " > '" +
                              dir.file("viewer.log") + "' 2>&1";
  constexpr int kAttempts = 3;
  int status = 0;
  for (int attempt = 1; attempt <= kAttempts; ++attempt) {
    status = std::system(command.c_str());
    if (status == 0 || viewerLog(dir).find("Failed to open display") == std::string::npos) break;
    std::fprintf(stderr, "attempt %d of %d: the viewer could not reach Xvfb; starting the session again\n%s\n", attempt,
                 kAttempts, viewerLog(dir).c_str());
  }
  if (status != 0) ADD_FAILURE() << command << "\n" << viewerLog(dir);
  return status;
}

// PLUMB_TEST_SCREENSHOTS=DIR keeps a session's screenshots there, for a person to look at, and
// its script and scene dump as <test>.session.json and <test>.scene.json, for scripts/replay-check
// to compare replays.
inline void keepScreenshots(const TempDirectory& dir) {
  const char* keep = std::getenv("PLUMB_TEST_SCREENSHOTS");
  if (keep == nullptr) return;
  const std::filesystem::path to(keep);
  std::filesystem::create_directories(to);
  const std::filesystem::path shots = dir.file("shots");
  if (std::filesystem::exists(shots)) {
    for (const auto& entry : std::filesystem::directory_iterator(shots)) {
      std::filesystem::copy_file(entry.path(), to / entry.path().filename(),
                                 std::filesystem::copy_options::overwrite_existing);
    }
  }
  const std::string test = ::testing::UnitTest::GetInstance()->current_test_info()->name();
  for (const char* kept : {"session", "scene"}) {
    const std::filesystem::path from = dir.file(std::string(kept) + ".json");
    if (std::filesystem::exists(from)) {
      std::filesystem::copy_file(from, to / (test + "." + kept + ".json"), std::filesystem::copy_options::overwrite_existing);
    }
  }
}

}  // namespace plumb::test
