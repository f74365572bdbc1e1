// Saves that survive a kill (issue 21, point 3): `plumb view` is stopped with SIGKILL 50 times,
// at moments drawn from a seeded generator (half of them while it saves), while its script draws
// rectangles, saves with Ctrl+S and the autosave runs every half second. After every kill the project opens (its file or the
// autosave, as the next session would), and holds at least what the last save or autosave the
// viewer reported held: a kill loses at most the edits since then, never what was on disk. The
// temporary files a killed save leaves go with the next save.
//
// One Xvfb serves all the sessions, so that the test kills the viewer itself, not xvfb-run; it
// must not reset when its last client goes (-noreset), or the next session finds no display.

#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <optional>
#include <random>
#include <regex>
#include <string>
#include <thread>

#include "tests/support/temp_directory.h"
#include "tests/ui/viewer_session.h"
#include "ui/viewer/project_session.h"

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

constexpr int kKills = 50;

// An X server of the test's own, on the display it chose (-displayfd), stopped at the end.
class OwnXvfb {
 public:
  OwnXvfb() {
    int pipe_fds[2];
    if (::pipe(pipe_fds) != 0) return;
    pid_ = ::fork();
    if (pid_ == 0) {
      ::close(pipe_fds[0]);
      const std::string fd = std::to_string(pipe_fds[1]);
      ::execlp("Xvfb", "Xvfb", "-displayfd", fd.c_str(), "-screen", "0", "1280x720x24", "-nolisten", "tcp", "-noreset",
               static_cast<char*>(nullptr));
      _exit(127);
    }
    ::close(pipe_fds[1]);
    // The number and its newline come in separate writes; closing the pipe before the newline
    // would kill the server (it cannot write it).
    std::string number;
    for (char c = 0; ::read(pipe_fds[0], &c, 1) == 1 && c != '\n';) number += c;
    ::close(pipe_fds[0]);
    if (!number.empty()) display_ = ":" + number;
  }
  ~OwnXvfb() {
    if (pid_ <= 0) return;
    ::kill(pid_, SIGTERM);
    ::waitpid(pid_, nullptr, 0);
  }
  OwnXvfb(const OwnXvfb&) = delete;
  OwnXvfb& operator=(const OwnXvfb&) = delete;

  const std::string& display() const { return display_; }

 private:
  pid_t pid_ = -1;
  std::string display_;
};

// Starts `plumb view` on `display`, its output into `log`; returns its pid.
pid_t startViewer(const std::string& display, const std::vector<std::string>& arguments, const std::string& log) {
  const pid_t child = ::fork();
  if (child != 0) return child;
  const int out = ::open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  ::dup2(out, 1);
  ::dup2(out, 2);
  ::setenv("DISPLAY", display.c_str(), 1);
  ::setenv("PLUMB_GPU", "cpu", 1);
  std::vector<char*> argv{const_cast<char*>(PLUMB_BINARY), const_cast<char*>("view")};
  for (const std::string& argument : arguments) argv.push_back(const_cast<char*>(argument.c_str()));
  argv.push_back(nullptr);
  ::execv(PLUMB_BINARY, argv.data());
  _exit(127);
}

// The polygons of the last save or autosave the session's log reports; none before the first.
std::optional<std::size_t> lastReportedPolygons(const std::string& log) {
  std::ifstream in(log);
  const std::regex saved(R"(plumb view: (saved|autosaved) .* \(\d+ segments, (\d+) polygons\))");
  std::optional<std::size_t> polygons;
  for (std::string line; std::getline(in, line);) {
    std::smatch match;
    if (std::regex_search(line, match, saved)) polygons = std::stoul(match[2]);
  }
  return polygons;
}

// Rectangles from three points on the floor (10 cm squares on a grid, Rectangle mode on), one
// after another, with a save after every other: more than a session lives to draw.
json drawingAndSaving() {
  json steps = json::array({{{"wait", "streaming_idle"}, {"timeout_s", 300}},
                            {{"look", {{"position", {1.6, 1.4, 2.2}}, {"target", {1.6, 1.5, 0.0}}}}},
                            {{"wait", "streaming_idle"}, {"timeout_s", 300}},
                            {{"tool", "polygon"}},
                            {{"key", "R"}}});
  for (int i = 0; i < 300; ++i) {
    const double x = 0.9 + 0.15 * (i % 10), y = 0.9 + 0.15 * (i / 10 % 8);
    for (const auto& [dx, dy] : {std::pair{0.0, 0.0}, std::pair{0.1, 0.0}, std::pair{0.1, 0.1}}) {
      steps.push_back({{"click_world", {x + dx, y + dy, 0.0}}});
      steps.push_back({{"wait", "frames"}, {"count", 1}});
    }
    if (i % 2 == 0) {
      steps.push_back({{"key_down", "LEFT_CONTROL"}});
      steps.push_back({{"key", "S"}});
      steps.push_back({{"key_up", "LEFT_CONTROL"}});
    }
  }
  return steps;
}

TEST(KilledSession, EveryKillLeavesAProjectThatOpensWithWhatWasLastSaved) {
  const plumb::test::TempDirectory dir;
  const std::string ply = dir.file("room.ply"), cloud = dir.file("room.plumb");
  const std::string prepare = std::string("'") + PLUMB_BINARY + "' simulate --scene room --points 100000 -o '" + ply +
                              "' >/dev/null && '" + PLUMB_BINARY + "' import '" + ply + "' -o '" + cloud +
                              "' >/dev/null";
  ASSERT_EQ(std::system(prepare.c_str()), 0);
  const std::string project = dir.file("room.plumbproj"), script = dir.file("session.json"), log = dir.file("viewer.log");
  std::ofstream(script) << drawingAndSaving().dump(1);
  const OwnXvfb xvfb;
  ASSERT_FALSE(xvfb.display().empty()) << "Xvfb did not start";

  // Odd kills come anywhere in the first seconds (the start, the opening, the first edits); even
  // ones up to 2 s after the session's first save, whatever the machine's speed.
  std::mt19937 random(21);  // the same kill moments on every run
  std::uniform_int_distribution<int> anywhere_ms(200, 4000), after_save_ms(0, 2000);
  std::size_t opened_before = 0;
  int kills_after_a_save = 0;
  for (int kill = 1; kill <= kKills; ++kill) {
    const pid_t viewer = startViewer(xvfb.display(),
                                     {cloud, "--project", project, "--script", script, "--autosave-s", "0.5",
                                      "--width", "1280", "--height", "720"},
                                     log);
    ASSERT_GT(viewer, 0);
    if (kill % 2 == 1) {
      std::this_thread::sleep_for(std::chrono::milliseconds(anywhere_ms(random)));
    } else {
      const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(300);
      while (!lastReportedPolygons(log) && std::chrono::steady_clock::now() < give_up) {
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(after_save_ms(random)));
    }
    ::kill(viewer, SIGKILL);
    int status = 0;
    ASSERT_EQ(::waitpid(viewer, &status, 0), viewer);
    ASSERT_TRUE(WIFSIGNALED(status)) << "kill " << kill << ": the session ended before it (" << status << ")\n"
                                     << std::ifstream(log).rdbuf();

    const std::optional<std::size_t> last_saved = lastReportedPolygons(log);
    if (last_saved) ++kills_after_a_save;
    const std::size_t reported = last_saved.value_or(0);
    std::optional<plumb::cad::Project> opened;
    try {
      opened = plumb::viewer::ProjectSession::open(project, cloud).takeOpened();
    } catch (const std::exception& error) {
      FAIL() << "kill " << kill << ": the project does not open: " << error.what();
    }
    const std::size_t polygons = opened ? opened->polygons.size() : 0;
    EXPECT_GE(polygons, reported) << "kill " << kill << ": a reported save is lost";
    EXPECT_GE(polygons, opened_before) << "kill " << kill << ": work an earlier session had on disk is lost";
    opened_before = polygons;
  }
  std::printf("%d kills, %d of them after the session had saved; %zu rectangles kept in all\n", kKills,
              kills_after_a_save, opened_before);
  EXPECT_GE(kills_after_a_save, kKills / 2) << "most kills must come while the session saves";

  // A last session saves and closes: the temporaries of the killed saves are gone.
  const json save = json::array({{{"wait", "streaming_idle"}, {"timeout_s", 300}},
                                 {{"key_down", "LEFT_CONTROL"}},
                                 {{"key", "S"}},
                                 {{"key_up", "LEFT_CONTROL"}}});
  ASSERT_EQ(plumb::test::runViewerSession(dir, "'" + cloud + "' --project '" + project + "'", save, 1280, 720), 0);
  for (const auto& entry : fs::directory_iterator(dir.path())) {
    EXPECT_EQ(entry.path().filename().string().find(".partial-"), std::string::npos) << entry.path();
  }
  EXPECT_FALSE(fs::exists(project + ".autosave")) << "a save takes the autosave's place";
}

}  // namespace
