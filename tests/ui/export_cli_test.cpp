// plumb export as a user runs it: a project to glTF, OBJ, DXF and CSV (corners, measurements), all
// of them or none.

#include <gtest/gtest.h>

#include <filesystem>

#include "cad/project_file.h"
#include "tests/cad/sample_project.h"
#include "tests/support/plumb_command.h"
#include "tests/support/temp_directory.h"

namespace {

using Outcome = plumb::test::CommandOutcome;

class ExportCli : public ::testing::Test {
 protected:
  void SetUp() override { plumb::cad::writeProjectFile(plumb::cad::test::sampleProject(), project_); }

  // Runs `plumb export` with `arguments` (shell words).
  Outcome plumbExport(const std::string& arguments) const {
    return plumb::test::runPlumb(temp_, "export " + arguments);
  }
  std::string path(const std::string& name) const { return temp_.file(name); }
  std::string allFive() const {
    return " --gltf " + path("room.glb") + " --obj " + path("room.obj") + " --dxf " + path("room.dxf") + " --csv " +
           path("room.csv") + " --measurements " + path("room-measurements.csv");
  }

  plumb::test::TempDirectory temp_;
  std::string project_ = temp_.file("room.plumbproj");
};

TEST_F(ExportCli, WritesEveryFormatAndSaysWhat) {
  const Outcome run = plumbExport(project_ + allFive());
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NE(run.out.find("3 segments, 3 edges, 2 corners, 2 polygons, 1 prism, 6 measurements, 2 groups"),
            std::string::npos)
      << run.out;
  for (const char* name : {"room.glb", "room.obj", "room.dxf", "room.csv", "room-measurements.csv"}) {
    EXPECT_NE(run.out.find("wrote  " + path(name)), std::string::npos) << run.out;
  }
  EXPECT_EQ(temp_.entryCount(), 6u) << "the project and the five outputs, no temporary";
  EXPECT_EQ(plumb::test::readFile(path("room.glb")).substr(0, 4), "glTF");
  EXPECT_NE(plumb::test::readFile(path("room.obj")).find("\no window_1\n"), std::string::npos);
  EXPECT_NE(plumb::test::readFile(path("room.dxf")).find("AC1015"), std::string::npos);
  EXPECT_EQ(plumb::test::readFile(path("room.csv")).rfind("id,name,x,y,z,", 0), 0u);
  EXPECT_EQ(plumb::test::readFile(path("room-measurements.csv")).rfind("id,name,kind,value,unit,", 0), 0u);
}

TEST_F(ExportCli, ACorruptProjectWritesNothing) {
  const std::string text = plumb::test::readFile(project_);
  plumb::test::writeFile(project_, text.substr(0, text.size() / 3));
  const Outcome run = plumbExport(project_ + allFive());
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_NE(run.err.find("plumb export: error: '" + project_ + "' at byte "), std::string::npos) << run.err;
  EXPECT_EQ(temp_.entryCount(), 1u) << "the project only";
}

TEST_F(ExportCli, AFailingOutputLeavesNoneOfTheOthers) {
  const Outcome run = plumbExport(project_ + " --gltf " + path("room.glb") + " --obj " + path("room.obj") + " --dxf " +
                                  path("nowhere/room.dxf") + " --csv " + path("room.csv"));
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_NE(run.err.find("plumb export: error: '" + path("nowhere/room.dxf") + "'"), std::string::npos) << run.err;
  EXPECT_EQ(temp_.entryCount(), 1u) << "the project only";
}

TEST_F(ExportCli, NeedsAnOutputAndKeepsTheProject) {
  const Outcome none = plumbExport(project_);
  EXPECT_EQ(none.exit_code, 1);
  EXPECT_NE(none.err.find("nothing to export: give at least one of --gltf, --obj, --dxf, --csv"), std::string::npos)
      << none.err;
  const Outcome over = plumbExport(project_ + " --obj " + project_);
  EXPECT_EQ(over.exit_code, 1);
  EXPECT_NE(over.err.find("--obj would overwrite the project"), std::string::npos) << over.err;
  const Outcome missing = plumbExport(path("absent.plumbproj") + " --csv " + path("room.csv"));
  EXPECT_EQ(missing.exit_code, 1);
  EXPECT_NE(missing.err.find(path("absent.plumbproj")), std::string::npos) << missing.err;
  EXPECT_EQ(temp_.entryCount(), 1u) << "the project only";
}

}  // namespace
