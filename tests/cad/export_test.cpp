#include "cad/export.h"

#include <gtest/gtest.h>

#include "engine/core/error.h"
#include "tests/cad/sample_project.h"
#include "tests/support/temp_directory.h"

namespace plumb::cad {
namespace {

std::string errorOf(const Project& project, const ExportTargets& targets) {
  try {
    exportAll(project, targets);
  } catch (const Error& error) {
    return error.what();
  }
  return "";
}

ExportTargets targetsIn(const plumb::test::TempDirectory& directory) {
  return {directory.file("room.glb"), directory.file("room.obj"), directory.file("room.dxf"),
          directory.file("room.csv"), directory.file("room-measurements.csv")};
}

TEST(ExportAll, WritesEveryFormatAsked) {
  plumb::test::TempDirectory directory;
  const ExportTargets targets = targetsIn(directory);
  const std::vector<std::string> written = exportAll(test::sampleProject(), targets);
  EXPECT_EQ(written,
            (std::vector<std::string>{targets.gltf, targets.obj, targets.dxf, targets.csv, targets.measurements}));
  EXPECT_EQ(directory.entryCount(), 5u) << "the five outputs and no temporary";
  EXPECT_EQ(plumb::test::readFile(targets.gltf).substr(0, 4), "glTF");
  EXPECT_EQ(plumb::test::readFile(targets.dxf).substr(0, 12), "  0\nSECTION\n");

  EXPECT_EQ(
      exportAll(test::sampleProject(), {.gltf = "", .obj = "", .dxf = "", .csv = targets.csv, .measurements = ""}),
      std::vector<std::string>{targets.csv});
  EXPECT_TRUE(exportAll(test::sampleProject(), {}).empty());
}

TEST(ExportAll, AFailingOutputLeavesNoneOfThem) {
  plumb::test::TempDirectory directory;
  ExportTargets targets = targetsIn(directory);
  plumb::test::writeFile(targets.obj, "an older export\n");
  targets.dxf = directory.file("nowhere/room.dxf");
  const std::string message = errorOf(test::sampleProject(), targets);
  EXPECT_EQ(message.rfind("'" + targets.dxf + "'", 0), 0u) << message;
  EXPECT_EQ(directory.entryCount(), 1u) << "only the older OBJ, untouched";
  EXPECT_EQ(plumb::test::readFile(targets.obj), "an older export\n");
}

TEST(ExportAll, AnInvalidProjectWritesNothing) {
  plumb::test::TempDirectory directory;
  Project project = test::sampleProject();
  project.edges[0].segments[0] = 40;
  const std::string message = errorOf(project, targetsIn(directory));
  EXPECT_NE(message.find("not exporting an invalid project: field 'edges[0].segments[0]'"), std::string::npos)
      << message;
  EXPECT_EQ(directory.entryCount(), 0u);
}

TEST(ExportAll, TwoFormatsCannotShareAFile) {
  plumb::test::TempDirectory directory;
  ExportTargets targets = targetsIn(directory);
  targets.csv = directory.path().string() + "/./room.obj";
  const std::string message = errorOf(test::sampleProject(), targets);
  EXPECT_NE(message.find("the OBJ and the CSV export both name this file"), std::string::npos) << message;
  EXPECT_EQ(directory.entryCount(), 0u);
}

}  // namespace
}  // namespace plumb::cad
