#include "cad/export_dxf.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <nlohmann/json.hpp>
#include <optional>

#include "cad/polygon_mesh.h"
#include "tests/cad/sample_project.h"
#include "tests/support/temp_directory.h"

namespace plumb::cad {
namespace {

constexpr double kWcsTolerance = 1e-6;  // metres: OCS there and back in double at UTM coordinates

// A Python 3 that has ezdxf (Debian's python3-ezdxf, which scripts/setup installs): the one on
// PATH, else Debian's own (PATH may lead to another installation first).
std::optional<std::string> pythonWithEzdxf() {
  for (const char* python : {"python3", "/usr/bin/python3"}) {
    if (std::system((std::string(python) + " -c 'import ezdxf' >/dev/null 2>&1").c_str()) == 0) return python;
  }
  return std::nullopt;
}

// What tests/cad/read_dxf.py reports of `path`.
nlohmann::json readWithEzdxf(const std::string& python, const std::string& path, const std::string& out) {
  const std::string command =
      python + " " + PLUMB_SOURCE_DIR + "/tests/cad/read_dxf.py " + path + " >" + out + " 2>" + out + ".err";
  const int status = std::system(command.c_str());
  EXPECT_EQ(status, 0) << plumb::test::readFile(out + ".err");
  return nlohmann::json::parse(plumb::test::readFile(out));
}

Eigen::Vector3d vector(const nlohmann::json& xyz) {
  return {xyz.at(0).get<double>(), xyz.at(1).get<double>(), xyz.at(2).get<double>()};
}

void expectVertices(const nlohmann::json& got, const std::vector<Eigen::Vector3d>& want, const std::string& what) {
  ASSERT_EQ(got.size(), want.size()) << what;
  for (std::size_t i = 0; i < want.size(); ++i) {
    EXPECT_LT((vector(got[i]) - want[i]).norm(), kWcsTolerance) << what << " vertex " << i;
  }
}

TEST(ExportDxf, EzdxfReadsAndAuditsItLayerByLayer) {
  const std::optional<std::string> python = pythonWithEzdxf();
  if (!python) GTEST_SKIP() << "python3-ezdxf is not installed (scripts/setup installs it)";
  plumb::test::TempDirectory directory;
  const Project project = test::sampleProject();
  const std::string path = directory.file("room.dxf");
  exportDxf(project, path);
  const nlohmann::json dxf = readWithEzdxf(*python, path, directory.file("dxf.json"));

  EXPECT_EQ(dxf["version"], "AC1015");
  EXPECT_EQ(dxf["units"], 6) << "metres";
  EXPECT_TRUE(dxf["audit_errors"].empty()) << dxf["audit_errors"].dump(1);
  EXPECT_TRUE(dxf["audit_fixes"].empty()) << dxf["audit_fixes"].dump(1);
  // ezdxf adds layers of its own as it loads (Defpoints); ours must be there.
  for (const char* layer : {"0", kDxfPolygonLayer, kDxfPrismLayer, kDxfSegmentLayer, kDxfEdgeLayer, kDxfCornerLayer}) {
    EXPECT_TRUE(std::find(dxf["layers"].begin(), dxf["layers"].end(), layer) != dxf["layers"].end()) << layer;
  }

  std::size_t outline_triangles = 0, outline_rings = 0;
  for (const Segment& segment : project.segments) {
    outline_triangles += segment.outline.shape.triangles.size();
    outline_rings += segment.outline.shape.rings.size();
  }
  const nlohmann::json expected_counts = {
      {"PLUMB_POLYGONS", {{"3DFACE", 2 + 4}, {"LWPOLYLINE", 2}}},
      {"PLUMB_PRISMS", {{"3DFACE", 12}, {"LWPOLYLINE", 2}}},
      {"PLUMB_SEGMENTS", {{"3DFACE", outline_triangles}, {"LWPOLYLINE", outline_rings}}},
      {"PLUMB_EDGES", {{"LINE", 3}}},
      {"PLUMB_CORNERS", {{"POINT", 2}}}};
  EXPECT_EQ(dxf["counts"], expected_counts) << dxf["counts"].dump(1);

  // The rings, from their OCS back to world coordinates by ezdxf: the window on the wall (its
  // normal -y), the L on the floor, the box's base and top.
  const nlohmann::json& polylines = dxf["polylines"];
  ASSERT_GE(polylines.size(), 4u);
  for (const auto& polyline : polylines) EXPECT_TRUE(polyline["closed"].get<bool>());
  expectVertices(polylines[0]["wcs"], project.polygons[0].vertices, "window");
  expectVertices(polylines[1]["wcs"], project.polygons[1].vertices, "L");
  expectVertices(polylines[2]["wcs"], project.polygons[2].vertices, "box base");
  std::vector<Eigen::Vector3d> top = project.polygons[2].vertices;
  for (Eigen::Vector3d& p : top) p += project.polygons[2].extrusion;
  expectVertices(polylines[3]["wcs"], top, "box top");
  // The floor's outer ring.
  const reco::PlaneOutline& floor = project.segments[0].outline;
  std::vector<Eigen::Vector3d> ring;
  for (const Eigen::Vector2d& p : floor.shape.rings[0]) ring.push_back(floor.toWorld(p));
  expectVertices(polylines[4]["wcs"], ring, "floor outline");

  // A face of the window, the edges, the corners.
  const TriangleMesh window = triangulatePolygon(project.polygons[0].vertices);
  const auto& [a, b, c] = window.triangles[0];
  expectVertices(dxf["faces"][0]["vertices"], {window.positions[a], window.positions[b], window.positions[c]},
                 "window face");
  for (std::size_t i = 0; i < project.edges.size(); ++i) {
    expectVertices(nlohmann::json::array({dxf["lines"][i]["start"], dxf["lines"][i]["end"]}),
                   {project.edges[i].start, project.edges[i].end}, "edge");
  }
  for (std::size_t i = 0; i < project.corners.size(); ++i) {
    expectVertices(nlohmann::json::array({dxf["points"][i]["position"]}), {project.corners[i].position}, "corner");
  }
}

TEST(ExportDxf, AnEmptyProjectIsAValidDrawing) {
  const std::optional<std::string> python = pythonWithEzdxf();
  if (!python) GTEST_SKIP() << "python3-ezdxf is not installed (scripts/setup installs it)";
  plumb::test::TempDirectory directory;
  const std::string path = directory.file("empty.dxf");
  exportDxf(Project{}, path);
  const nlohmann::json dxf = readWithEzdxf(*python, path, directory.file("dxf.json"));
  EXPECT_TRUE(dxf["audit_errors"].empty()) << dxf["audit_errors"].dump(1);
  EXPECT_TRUE(dxf["counts"].empty());
}

}  // namespace
}  // namespace plumb::cad
