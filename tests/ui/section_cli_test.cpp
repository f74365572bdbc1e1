// plumb section as a user runs it: the floor plan of a project's walls as DXF and SVG, both or
// neither.

#include <gtest/gtest.h>

#include <filesystem>

#include "cad/project_file.h"
#include "tests/cad/sample_project.h"
#include "tests/support/plumb_command.h"
#include "tests/support/temp_directory.h"

namespace {

using Outcome = plumb::test::CommandOutcome;

// The sample project (tests/cad/sample_project.h): a floor and two walls meeting at its corner.
class SectionCli : public ::testing::Test {
 protected:
  void SetUp() override { plumb::cad::writeProjectFile(plumb::cad::test::sampleProject(), project_); }

  Outcome plumbSection(const std::string& arguments) const {
    return plumb::test::runPlumb(temp_, "section " + arguments);
  }
  std::string path(const std::string& name) const { return temp_.file(name); }

  plumb::test::TempDirectory temp_;
  std::string project_ = temp_.file("room.plumbproj");
};

TEST_F(SectionCli, CutsTheWallsAboveTheFloorIntoADxfAndAnSvg) {
  const Outcome run =
      plumbSection(project_ + " --height 1.0 --above-floor --dxf " + path("plan.dxf") + " --svg " + path("plan.svg"));
  ASSERT_EQ(run.exit_code, 0) << run.err;
  // The floor's lowest point is a little below the origin's z (it is tilted by 2e-4): the section
  // lies 1 m above that.
  EXPECT_NE(run.out.find("2 wall faces cut, 2 lines, 1 corners joined, 0 closed outlines, 0 openings"),
            std::string::npos)
      << run.out;
  EXPECT_NE(run.out.find("wrote  " + path("plan.dxf")), std::string::npos) << run.out;
  EXPECT_EQ(temp_.entryCount(), 3u) << "the project and the two drawings, no temporary";
  const std::string dxf = plumb::test::readFile(path("plan.dxf"));
  EXPECT_NE(dxf.find("AC1015"), std::string::npos);
  EXPECT_NE(dxf.find("PLAN_WALLS"), std::string::npos);
  const std::string svg = plumb::test::readFile(path("plan.svg"));
  EXPECT_EQ(svg.rfind("<?xml", 0), 0u);
  EXPECT_NE(svg.find("<polyline points="), std::string::npos) << "the two walls as one open line";
}

TEST_F(SectionCli, WithoutAFloorAboveFloorIsAnError) {
  plumb::cad::Project project = plumb::cad::test::sampleProject();
  project.segments.erase(project.segments.begin());  // the floor
  project.edges.clear();
  project.corners.clear();
  project.polygons.clear();
  project.measurements.clear();
  plumb::cad::writeProjectFile(project, project_);
  const Outcome run = plumbSection(project_ + " --height 1.0 --above-floor --svg " + path("plan.svg"));
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_NE(run.err.find("the project has no floor"), std::string::npos) << run.err;
  const Outcome world = plumbSection(project_ + " --height 251.0 --svg " + path("plan.svg"));
  EXPECT_EQ(world.exit_code, 0) << world.err;
}

TEST_F(SectionCli, BadArgumentsAndAFailingOutputWriteNothing) {
  const Outcome none = plumbSection(project_ + " --height 1");
  EXPECT_EQ(none.exit_code, 1);
  EXPECT_NE(none.err.find("nothing to write: give --dxf, --svg or both"), std::string::npos) << none.err;
  const Outcome same = plumbSection(project_ + " --height 1 --dxf " + path("a") + " --svg " + path("a"));
  EXPECT_EQ(same.exit_code, 1);
  EXPECT_NE(same.err.find("both name this file"), std::string::npos) << same.err;
  const Outcome over = plumbSection(project_ + " --height 1 --svg " + project_);
  EXPECT_EQ(over.exit_code, 1);
  EXPECT_NE(over.err.find("would overwrite the project"), std::string::npos) << over.err;
  const Outcome nan = plumbSection(project_ + " --height nan --svg " + path("plan.svg"));
  EXPECT_NE(nan.exit_code, 0);
  const Outcome missing_folder =
      plumbSection(project_ + " --height 1 --dxf " + path("plan.dxf") + " --svg " + path("nowhere/plan.svg"));
  EXPECT_EQ(missing_folder.exit_code, 1);
  EXPECT_NE(missing_folder.err.find(path("nowhere/plan.svg")), std::string::npos) << missing_folder.err;
  const std::string text = plumb::test::readFile(project_);
  plumb::test::writeFile(project_, text.substr(0, text.size() / 2));
  const Outcome corrupt = plumbSection(project_ + " --height 1 --svg " + path("plan.svg"));
  EXPECT_EQ(corrupt.exit_code, 1);
  EXPECT_NE(corrupt.err.find("plumb section: error: '" + project_ + "' at byte "), std::string::npos) << corrupt.err;
  EXPECT_EQ(temp_.entryCount(), 1u) << "the project only";
}

}  // namespace
