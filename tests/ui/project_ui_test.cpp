// Projects in the viewer (issue 7, point 8): a session that ends unsaved leaves an autosave, and
// the next session of that project opens it (nothing is lost); a corrupt project file stops the
// viewer with a message naming the file and the place, and is left as it was.

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "tests/support/temp_directory.h"
#include "tests/ui/viewer_session.h"

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

std::string readFile(const std::string& path) {
  std::ifstream in(path);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

TEST(ViewerProject, UnsavedWorkIsKeptInTheAutosaveAndRecoveredByTheNextSession) {
  const plumb::test::TempDirectory dir;
  const std::string ply = dir.file("room.ply");
  const std::string simulate = std::string("'") + PLUMB_BINARY +
                               "' simulate --scene room --points 300000 --noise-mm 2 -o '" + ply + "' >/dev/null";
  ASSERT_EQ(std::system(simulate.c_str()), 0);
  const std::string project = dir.file("room.plumbproj");
  const json look = {{"look", {{"position", {3.5, 2.5, 1.5}}, {"target", {3.5, 5.0, 1.5}}}}};
  // Session 1: a grow on the y+ wall (where no panel covers it), then the window closes unsaved.
  const json grow = json::array({{{"wait", "streaming_idle"}, {"timeout_s", 300}},
                                 look,
                                 {{"wait", "streaming_idle"}, {"timeout_s", 300}},
                                 {{"click_world", {3.0, 5.0, 2.3}}},  // the wall above the window
                                 {{"wait", "grower_idle"}, {"timeout_s", 300}}});
  ASSERT_EQ(plumb::test::runViewerSession(dir, "'" + ply + "' --project '" + project + "'", grow, 1280, 720), 0);
  const json first = plumb::test::readJson(dir.file("scene.json"));
  ASSERT_GE(first.at("segments").size(), 1u);
  EXPECT_FALSE(fs::exists(project)) << "only Save writes the project";
  ASSERT_TRUE(fs::exists(project + ".autosave")) << plumb::test::viewerLog(dir);
  EXPECT_NE(plumb::test::viewerLog(dir).find("unsaved changes kept in"), std::string::npos);

  // Session 2: the project (its cloud from the autosave) opens with the grown segments; a save
  // writes them to the project and the autosave goes.
  const json save = json::array({{{"wait", "streaming_idle"}, {"timeout_s", 300}},
                                 {{"key_down", "LEFT_CONTROL"}},
                                 {{"key", "S"}},
                                 {{"key_up", "LEFT_CONTROL"}}});
  ASSERT_EQ(plumb::test::runViewerSession(dir, "--project '" + project + "'", save, 1280, 720), 0);
  EXPECT_NE(plumb::test::viewerLog(dir).find("recovered unsaved work"), std::string::npos)
      << plumb::test::viewerLog(dir);
  const json second = plumb::test::readJson(dir.file("scene.json"));
  ASSERT_EQ(second.at("segments").size(), first.at("segments").size());
  EXPECT_EQ(second.at("segments")[0].at("normal"), first.at("segments")[0].at("normal"));
  EXPECT_TRUE(fs::exists(project));
  EXPECT_FALSE(fs::exists(project + ".autosave"));
  EXPECT_EQ(plumb::test::readJson(project).at("segments").size(), first.at("segments").size());
}

TEST(ViewerProject, ACorruptProjectStopsTheViewerAndIsLeftAsItWas) {
  const plumb::test::TempDirectory dir;
  const std::string project = dir.file("broken.plumbproj");
  const std::string broken = R"({"format": "plumb-project", "version": 1, "segments": [)";  // truncated
  std::ofstream(project) << broken;
  // Without a display too: the project is read before the viewer looks for one.
  const std::string command = std::string("env -u DISPLAY PLUMB_GPU=cpu '") + PLUMB_BINARY + "' view --project '" +
                              project + "' > '" + dir.file("out.txt") + "' 2>&1";
  EXPECT_NE(std::system(command.c_str()), 0);
  const std::string out = readFile(dir.file("out.txt"));
  EXPECT_NE(out.find("broken.plumbproj"), std::string::npos) << out;
  EXPECT_NE(out.find("byte"), std::string::npos) << "the place in the file: " << out;
  EXPECT_EQ(readFile(project), broken);
  EXPECT_FALSE(fs::exists(project + ".autosave"));
}

}  // namespace
