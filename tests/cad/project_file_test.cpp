#include "cad/project_file.h"

#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <bit>
#include <csignal>
#include <filesystem>
#include <functional>
#include <nlohmann/json.hpp>

#include "cad/project_validation.h"
#include "engine/core/error.h"
#include "tests/cad/sample_project.h"
#include "tests/support/temp_directory.h"

namespace plumb::cad {
namespace {

// Bit for bit: -0.0 differs from 0.0, and every NaN from itself only by its bits.
void expectSame(double a, double b, const std::string& what) {
  EXPECT_EQ(std::bit_cast<std::uint64_t>(a), std::bit_cast<std::uint64_t>(b)) << what << ": " << a << " vs " << b;
}
template <typename Derived>
void expectSame(const Eigen::MatrixBase<Derived>& a, const Eigen::MatrixBase<Derived>& b, const std::string& what) {
  for (Eigen::Index i = 0; i < a.size(); ++i) expectSame(a(i), b(i), what + "[" + std::to_string(i) + "]");
}

void expectSame(const view::Camera& a, const view::Camera& b) {
  expectSame(a.position, b.position, "camera.position");
  expectSame(a.target, b.target, "camera.target");
  expectSame(a.up, b.up, "camera.up");
  EXPECT_EQ(a.projection, b.projection);
  expectSame(a.fov_deg, b.fov_deg, "camera.fov_deg");
  expectSame(a.ortho_height_m, b.ortho_height_m, "camera.ortho_height_m");
  EXPECT_EQ(a.viewport_width_px, b.viewport_width_px);
  EXPECT_EQ(a.viewport_height_px, b.viewport_height_px);
  expectSame(a.near_m, b.near_m, "camera.near_m");
  expectSame(a.far_m, b.far_m, "camera.far_m");
}

void expectSame(const reco::Plane& a, const reco::Plane& b, const std::string& what) {
  EXPECT_EQ(a.valid, b.valid) << what;
  expectSame(a.normal, b.normal, what + ".normal");
  expectSame(a.tangent, b.tangent, what + ".tangent");
  expectSame(a.bitangent, b.bitangent, what + ".bitangent");
  expectSame(a.centroid, b.centroid, what + ".centroid");
  expectSame(a.offset, b.offset, what + ".offset");
  expectSame(a.lambda0, b.lambda0, what + ".lambda0");
  expectSame(a.lambda1, b.lambda1, what + ".lambda1");
  expectSame(a.lambda2, b.lambda2, what + ".lambda2");
  EXPECT_EQ(a.point_count, b.point_count) << what;
  expectSame(a.rms, b.rms, what + ".rms");
}

void expectSame(const reco::PlaneOutline& a, const reco::PlaneOutline& b, const std::string& what) {
  expectSame(a.origin, b.origin, what + ".origin");
  expectSame(a.axis_u, b.axis_u, what + ".axis_u");
  expectSame(a.axis_v, b.axis_v, what + ".axis_v");
  ASSERT_EQ(a.shape.rings.size(), b.shape.rings.size()) << what;
  for (std::size_t r = 0; r < a.shape.rings.size(); ++r) {
    ASSERT_EQ(a.shape.rings[r].size(), b.shape.rings[r].size()) << what;
    for (std::size_t v = 0; v < a.shape.rings[r].size(); ++v) {
      expectSame(a.shape.rings[r][v], b.shape.rings[r][v], what + ".rings");
    }
  }
  ASSERT_EQ(a.shape.vertices.size(), b.shape.vertices.size()) << what;
  for (std::size_t v = 0; v < a.shape.vertices.size(); ++v) {
    expectSame(a.shape.vertices[v], b.shape.vertices[v], what + ".vertices");
  }
  EXPECT_EQ(a.shape.triangles, b.shape.triangles) << what;
  expectSame(a.shape.area_m2, b.shape.area_m2, what + ".area_m2");
  expectSame(a.shape.cell_m, b.shape.cell_m, what + ".cell_m");
  EXPECT_EQ(a.shape.raster_width_cells, b.shape.raster_width_cells) << what;
  EXPECT_EQ(a.shape.raster_height_cells, b.shape.raster_height_cells) << what;
}

void expectSame(const Project& a, const Project& b) {
  EXPECT_EQ(a.cloud_path, b.cloud_path);
  ASSERT_EQ(a.camera.has_value(), b.camera.has_value());
  if (a.camera) expectSame(*a.camera, *b.camera);
  ASSERT_EQ(a.groups.size(), b.groups.size());
  for (std::size_t i = 0; i < a.groups.size(); ++i) {
    EXPECT_EQ(a.groups[i].id, b.groups[i].id);
    EXPECT_EQ(a.groups[i].name, b.groups[i].name);
  }
  ASSERT_EQ(a.segments.size(), b.segments.size());
  for (std::size_t i = 0; i < a.segments.size(); ++i) {
    const std::string what = "segments[" + std::to_string(i) + "]";
    EXPECT_EQ(a.segments[i].id, b.segments[i].id) << what;
    EXPECT_EQ(a.segments[i].name, b.segments[i].name) << what;
    EXPECT_EQ(a.segments[i].group, b.segments[i].group) << what;
    expectSame(a.segments[i].plane, b.segments[i].plane, what + ".plane");
    expectSame(a.segments[i].outline, b.segments[i].outline, what + ".outline");
  }
  ASSERT_EQ(a.edges.size(), b.edges.size());
  for (std::size_t i = 0; i < a.edges.size(); ++i) {
    EXPECT_EQ(a.edges[i].id, b.edges[i].id);
    EXPECT_EQ(a.edges[i].name, b.edges[i].name);
    EXPECT_EQ(a.edges[i].group, b.edges[i].group);
    EXPECT_EQ(a.edges[i].segments, b.edges[i].segments);
    expectSame(a.edges[i].start, b.edges[i].start, "edge start");
    expectSame(a.edges[i].end, b.edges[i].end, "edge end");
  }
  ASSERT_EQ(a.corners.size(), b.corners.size());
  for (std::size_t i = 0; i < a.corners.size(); ++i) {
    EXPECT_EQ(a.corners[i].id, b.corners[i].id);
    EXPECT_EQ(a.corners[i].name, b.corners[i].name);
    EXPECT_EQ(a.corners[i].group, b.corners[i].group);
    EXPECT_EQ(a.corners[i].segments, b.corners[i].segments);
    expectSame(a.corners[i].position, b.corners[i].position, "corner position");
    for (std::size_t k = 0; k < 3; ++k) expectSame(a.corners[i].support[k], b.corners[i].support[k], "support");
  }
  ASSERT_EQ(a.polygons.size(), b.polygons.size());
  for (std::size_t i = 0; i < a.polygons.size(); ++i) {
    EXPECT_EQ(a.polygons[i].id, b.polygons[i].id);
    EXPECT_EQ(a.polygons[i].name, b.polygons[i].name);
    EXPECT_EQ(a.polygons[i].group, b.polygons[i].group);
    EXPECT_EQ(a.polygons[i].plane, b.polygons[i].plane);
    ASSERT_EQ(a.polygons[i].vertices.size(), b.polygons[i].vertices.size());
    for (std::size_t v = 0; v < a.polygons[i].vertices.size(); ++v) {
      expectSame(a.polygons[i].vertices[v], b.polygons[i].vertices[v], "polygon vertex");
    }
    expectSame(a.polygons[i].extrusion, b.polygons[i].extrusion, "extrusion");
  }
  ASSERT_EQ(a.measurements.size(), b.measurements.size());
  for (std::size_t i = 0; i < a.measurements.size(); ++i) {
    const Measurement& m = a.measurements[i];
    const Measurement& n = b.measurements[i];
    EXPECT_EQ(m.id, n.id);
    EXPECT_EQ(m.name, n.name);
    EXPECT_EQ(m.group, n.group);
    EXPECT_EQ(m.kind, n.kind);
    EXPECT_EQ(m.sources, n.sources);
    ASSERT_EQ(m.terms.size(), n.terms.size());
    for (std::size_t k = 0; k < m.terms.size(); ++k) {
      EXPECT_EQ(m.terms[k].kind, n.terms[k].kind);
      expectSame(m.terms[k].point, n.terms[k].point, "term point");
      expectSame(m.terms[k].direction, n.terms[k].direction, "term direction");
      ASSERT_EQ(m.terms[k].ring.size(), n.terms[k].ring.size());
      for (std::size_t v = 0; v < m.terms[k].ring.size(); ++v)
        expectSame(m.terms[k].ring[v], n.terms[k].ring[v], "ring");
    }
  }
}

TEST(ProjectFile, RoundTripsEveryFieldBitForBit) {
  plumb::test::TempDirectory directory;
  Project project = test::sampleProject();
  ASSERT_GE(project.segments[0].outline.shape.rings.size(), 2u) << "the floor's outline has its hole";
  // Numbers a short decimal cannot hold, and a negative zero.
  project.segments[1].plane.rms = 1.0 / 3.0;
  project.corners[1].support[2] = -0.0;
  project.polygons[0].name = "Fenster \"Süd\"\n2. Stock";
  const std::string path = directory.file("room.plumbproj");
  writeProjectFile(project, path);
  EXPECT_EQ(directory.entryCount(), 1u) << "no temporary file left";
  expectSame(readProjectFile(path), project);

  // Without a camera, groups or anything else: still the same value.
  const Project empty;
  writeProjectFile(empty, path);
  expectSame(readProjectFile(path), empty);
}

// The view's section (a slice, a slab, a turned box kept outside, a plane) comes back as it was; a
// section the renderer could not take is refused with its place; a version 1 file (no section)
// still reads.
TEST(ProjectFile, KeepsTheViewsSection) {
  plumb::test::TempDirectory directory;
  Project project = test::sampleProject();
  view::ClipSettings section;
  section.slice = true;
  section.slice_bottom_z = 1.15;
  section.slice_thickness = 0.1;
  section.slab = view::ClipSlab{{0.5, 5.0, 1.0}, {0.0, -1.0, 0.0}, 0.25};
  section.box = view::ClipBox{{3.5, 2.5, 1.25}, {1.0 / 3.0, 2.0, 0.75}, 0.3};
  section.keep_outside_box = true;
  section.planes.push_back({{1.0, 2.0, 3.0}, Eigen::Vector3d(1.0, 2.0, 2.0).normalized()});
  project.section = section;
  const std::string path = directory.file("room.plumbproj");
  writeProjectFile(project, path);
  const Project back = readProjectFile(path);
  ASSERT_TRUE(back.section.has_value());
  EXPECT_TRUE(back.section->slice);
  EXPECT_EQ(back.section->slice_bottom_z, 1.15);
  EXPECT_EQ(back.section->slice_thickness, 0.1);
  ASSERT_TRUE(back.section->slab.has_value());
  EXPECT_EQ(back.section->slab->point, section.slab->point);
  EXPECT_EQ(back.section->slab->normal, section.slab->normal);
  EXPECT_EQ(back.section->slab->thickness, 0.25);
  ASSERT_TRUE(back.section->box.has_value());
  EXPECT_EQ(back.section->box->centre, section.box->centre);
  EXPECT_EQ(back.section->box->half_size, section.box->half_size);
  EXPECT_EQ(back.section->box->yaw_rad, 0.3);
  EXPECT_TRUE(back.section->keep_outside_box);
  ASSERT_EQ(back.section->planes.size(), 1u);
  EXPECT_EQ(back.section->planes[0].normal, section.planes[0].normal);

  std::string text = plumb::test::readFile(path);
  text.replace(text.find("\"thickness\": 0.1"), 16, "\"thickness\": 0.0");
  plumb::test::writeFile(path, text);
  try {
    readProjectFile(path);
    ADD_FAILURE() << "a slice of no thickness was read";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("field 'section.slice.thickness': must be above 0"), std::string::npos)
        << error.what();
  }

  writeProjectFile(test::sampleProject(), path);
  text = plumb::test::readFile(path);
  EXPECT_EQ(text.find("\"section\""), std::string::npos) << "no section, no field";
  text.replace(text.find("\"version\": 3"), 12, "\"version\": 1");
  plumb::test::writeFile(path, text);
  EXPECT_FALSE(readProjectFile(path).section.has_value());
}

// A project without measurements is written as version 2, which the builds before them read.
TEST(ProjectFile, WithoutMeasurementsItIsVersionTwo) {
  plumb::test::TempDirectory directory;
  const std::string path = directory.file("room.plumbproj");
  Project project = test::sampleProject();
  project.measurements.clear();
  writeProjectFile(project, path);
  const std::string text = plumb::test::readFile(path);
  EXPECT_NE(text.find("\"version\": 2,"), std::string::npos) << text.substr(0, 80);
  EXPECT_EQ(readProjectFile(path).segments.size(), project.segments.size());
}

TEST(ProjectFile, IsReadableJsonWithFormatAndVersionFirst) {
  plumb::test::TempDirectory directory;
  const std::string path = directory.file("room.plumbproj");
  writeProjectFile(test::sampleProject(), path);
  const std::string text = plumb::test::readFile(path);
  EXPECT_EQ(text.rfind("{\n  \"format\": \"plumb-project\",\n  \"version\": 3,\n", 0), 0u) << text.substr(0, 80);
  EXPECT_NE(text.find("\"normal\": [1.0,0.0,0.0]"), std::string::npos) << "vectors on one line";
  const nlohmann::json json = nlohmann::json::parse(text);
  EXPECT_EQ(json["polygons"][2]["extrusion"][2], 0.8125);
  EXPECT_EQ(json["camera"]["viewport"][0], 1600);
}

// Writes the sample project, lets `edit` change its JSON (or, with `text_edit`, its text), and
// returns the error that reading it gives; "" when it reads.
class ProjectFileErrors : public ::testing::Test {
 protected:
  std::string errorFor(const std::function<void(nlohmann::json&)>& edit,
                       const std::function<void(std::string&)>& text_edit = nullptr) {
    writeProjectFile(test::sampleProject(), path_);
    nlohmann::json json = nlohmann::json::parse(plumb::test::readFile(path_));
    if (edit) edit(json);
    std::string text = json.dump(1);
    if (text_edit) text_edit(text);
    plumb::test::writeFile(path_, text);
    return errorReading();
  }
  std::string errorReading() const {
    try {
      readProjectFile(path_);
    } catch (const Error& error) {
      return error.what();
    }
    return "";
  }
  // The message names the file, quoted, first, then each of `parts`.
  void expectError(const std::string& message, const std::vector<std::string>& parts) const {
    ASSERT_FALSE(message.empty()) << "no error; expected: " << parts.front();
    EXPECT_EQ(message.rfind("'" + path_ + "'", 0), 0u) << message;
    for (const auto& part : parts) EXPECT_NE(message.find(part), std::string::npos) << message << "\nlacks: " << part;
  }

  plumb::test::TempDirectory directory_;
  std::string path_ = directory_.file("room.plumbproj");
};

TEST_F(ProjectFileErrors, NotJsonNamesTheByte) {
  expectError(errorFor(nullptr, [](std::string& text) { text.insert(text.find("\"groups\""), "NaN, "); }),
              {"' at byte ", "not a JSON Plumb project file"});
  // Truncated in the middle.
  expectError(errorFor(nullptr, [](std::string& text) { text.resize(text.size() / 2); }), {"' at byte ", "not a JSON"});
  plumb::test::writeFile(path_, "");
  expectError(errorReading(), {"the file is empty"});
  plumb::test::writeFile(path_, "[1, 2]");
  expectError(errorReading(), {"expected a JSON object (a Plumb project file), found array"});
}

TEST_F(ProjectFileErrors, FormatAndVersion) {
  expectError(errorFor([](nlohmann::json& j) { j["format"] = "plumb-camera"; }),
              {"field 'format'", "not a Plumb project file"});
  expectError(errorFor([](nlohmann::json& j) { j.erase("format"); }), {"field 'format': missing"});
  expectError(errorFor([](nlohmann::json& j) { j["version"] = 4; }),
              {"field 'version'", "written by a newer Plumb (version 4); this build reads up to 3"});
  expectError(errorFor([](nlohmann::json& j) { j["version"] = 0; }), {"field 'version'", "whole number"});
}

TEST_F(ProjectFileErrors, FieldsAreNamedByTheirJsonPath) {
  expectError(errorFor([](nlohmann::json& j) { j["polygons"][2].erase("vertices"); }),
              {"field 'polygons[2].vertices': missing"});
  expectError(errorFor([](nlohmann::json& j) { j["polygons"][2]["vertices"][1] = "x"; }),
              {"field 'polygons[2].vertices[1]': expected an array of 3 numbers"});
  expectError(errorFor([](nlohmann::json& j) { j["polygons"][2]["vertices"][1][0] = "x"; }),
              {"field 'polygons[2].vertices[1][0]': expected a number, found string"});
  expectError(errorFor([](nlohmann::json& j) { j["segments"][0]["plane"]["normall"] = 1; }),
              {"field 'segments[0].plane.normall': unknown field"});
  expectError(errorFor([](nlohmann::json& j) { j["edges"][1]["segments"] = {10}; }),
              {"field 'edges[1].segments': expected an array of 2 elements, found 1"});
  expectError(errorFor([](nlohmann::json& j) { j["segments"][1]["outline"]["triangles"][0][1] = -1; }),
              {"field 'segments[1].outline.triangles[0][1]': expected a whole number"});
  expectError(errorFor([](nlohmann::json& j) { j["groups"] = nlohmann::json::object(); }),
              {"field 'groups': expected an array, found object"});
}

TEST_F(ProjectFileErrors, NumbersBeyondADoubleAndRepeatedKeys) {
  expectError(errorFor([](nlohmann::json& j) { j["edges"][1]["start"][2] = 12345.5; },
                       [](std::string& text) { text.replace(text.find("12345.5"), 7, "1e999"); }),
              {"field 'edges[1].start[2]': a number is not finite"});
  expectError(errorFor(nullptr, [](std::string& text) { text.insert(1, "\"cloud\": \"a\","); }),
              {"field 'cloud': the key appears twice in one object"});
}

TEST_F(ProjectFileErrors, IdsAndReferences) {
  expectError(errorFor([](nlohmann::json& j) { j["polygons"][0]["id"] = 10; }),
              {"field 'polygons[0].id': id 10 is already the id of segments[0]"});
  expectError(errorFor([](nlohmann::json& j) { j["groups"][0]["id"] = 0; }),
              {"field 'groups[0].id': expected an id, a positive whole number"});
  expectError(errorFor([](nlohmann::json& j) { j["edges"][0]["segments"][1] = 99; }),
              {"field 'edges[0].segments[1]': refers to id 99, which no item of the project has"});
  expectError(errorFor([](nlohmann::json& j) { j["edges"][0]["segments"][0] = 40; }),
              {"field 'edges[0].segments[0]': refers to id 40, which is a polygon (polygons[0]), not a segment"});
  expectError(errorFor([](nlohmann::json& j) { j["polygons"][1]["group"] = 10; }),
              {"field 'polygons[1].group'", "which is a segment", "not a group"});
  expectError(errorFor([](nlohmann::json& j) { j["polygons"][0]["plane"] = 30; }),
              {"field 'polygons[0].plane'", "which is a corner"});
}

TEST_F(ProjectFileErrors, MeasurementsTheRulesRefuse) {
  expectError(errorFor([](nlohmann::json& j) { j["measurements"][0]["kind"] = "volume"; }),
              {"field 'measurements[0].kind'", "\"distance\", \"angle\""});
  expectError(errorFor([](nlohmann::json& j) { j["measurements"][1]["terms"][1]["kind"] = "edge"; }),
              {"field 'measurements[1].terms[1].kind'", "\"point\", \"plane\", \"line\" or \"polygon\""});
  expectError(errorFor([](nlohmann::json& j) { j["measurements"][0]["terms"].erase(1); }),
              {"field 'measurements[0].terms': Distance takes 2 terms, not 1"});
  expectError(errorFor([](nlohmann::json& j) {
                j["measurements"][4]["terms"][0]["kind"] = "point";
                j["measurements"][4]["terms"][0].erase("direction");
              }),
              {"field 'measurements[4].terms': Height: term 1 must be a plane, not a point"});
  expectError(errorFor([](nlohmann::json& j) {
                j["measurements"][3]["terms"][1]["direction"] = {0.0, 1.0, 0.0};
              }),
              {"field 'measurements[3].terms': the planes are 90.00", "from parallel", "measure their angle instead"});
  expectError(errorFor([](nlohmann::json& j) {
                j["measurements"][4]["terms"][0]["direction"] = {1.0, 0.0, 0.0};
              }),
              {"field 'measurements[4].terms': the floor is tilted 90.00"});
  expectError(errorFor([](nlohmann::json& j) {
                j["measurements"][1]["terms"][0]["direction"] = {0.5, 0.0, 0.0};
              }),
              {"field 'measurements[1].terms': term 1 (plane): its direction must be a unit vector"});
  expectError(errorFor([](nlohmann::json& j) {
                auto& ring = j["measurements"][5]["terms"][0]["ring"];
                ring[1] = ring[0];
              }),
              {"field 'measurements[5].terms': term 1 (polygon): "});
  expectError(errorFor([](nlohmann::json& j) { j["measurements"][0]["sources"] = {30}; }),
              {"field 'measurements[0].sources': must name one item (or 0) per term: 2 terms, 1 sources"});
  expectError(errorFor([](nlohmann::json& j) { j["measurements"][0]["sources"][1] = 2; }),
              {"field 'measurements[0].sources[1]': refers to id 2, which is a group (groups[1])"});
  expectError(errorFor([](nlohmann::json& j) { j["measurements"][0]["sources"][1] = 99; }),
              {"field 'measurements[0].sources[1]': refers to id 99, which no item of the project has"});
  expectError(errorFor([](nlohmann::json& j) {
                j["measurements"][0]["terms"][0]["direction"] = {1.0, 0.0, 0.0};
              }),
              {"field 'measurements[0].terms[0].direction': unknown field"});
  expectError(errorFor([](nlohmann::json& j) { j["measurements"][0].erase("sources"); }),
              {"field 'measurements[0].sources': missing"});
  expectError(errorFor([](nlohmann::json& j) { j["measurements"][2]["id"] = 30; }),
              {"field 'measurements[2].id': id 30 is already the id of corners[0]"});
}

TEST_F(ProjectFileErrors, GeometryTheRulesRefuse) {
  // A bow-tie: the L's vertices 1 and 3 swapped.
  expectError(
      errorFor([](nlohmann::json& j) { std::swap(j["polygons"][1]["vertices"][1], j["polygons"][1]["vertices"][3]); }),
      {"field 'polygons[1].vertices': the edge from vertex"});
  expectError(errorFor([](nlohmann::json& j) {
                j["polygons"][2]["extrusion"] = {0.5, 0.0, 0.0};
              }),
              {"field 'polygons[2].extrusion': the extrusion lies in the polygon's plane"});
  expectError(errorFor([](nlohmann::json& j) {
                j["segments"][1]["plane"]["normal"] = {0.9, 0.0, 0.0};
              }),
              {"field 'segments[1].plane.normal': must be a unit vector"});
  expectError(errorFor([](nlohmann::json& j) { j["segments"][1]["outline"]["triangles"][1][2] = 4; }),
              {"field 'segments[1].outline.triangles[1][2]': vertex 4 does not exist"});
  expectError(errorFor([](nlohmann::json& j) { j["camera"]["position"] = j["camera"]["target"]; }),
              {"field 'camera.target': must lie at least 1 micrometre from the position"});
  expectError(errorFor([](nlohmann::json& j) { j["camera"]["fov"] = 50; }), {"field 'camera.fov': unknown field"});
  expectError(errorFor([](nlohmann::json& j) { j["camera"]["target"][1] = "north"; }),
              {"field 'camera.target[1]': expected a number, found string"});
}

TEST_F(ProjectFileErrors, FilesThatCannotBeRead) {
  std::filesystem::remove(path_);
  expectError(errorReading(), {"cannot open the project file"});
  std::filesystem::create_directory(path_);
  expectError(errorReading(), {"is a directory"});
}

TEST(ProjectFile, AFailedWriteLeavesTheOldFile) {
  plumb::test::TempDirectory directory;
  const std::string path = directory.file("room.plumbproj");
  writeProjectFile(test::sampleProject(), path);
  const std::string before = plumb::test::readFile(path);

  // An invalid project is refused before anything is written.
  Project bad = test::sampleProject();
  bad.polygons[1].vertices.resize(2);
  try {
    writeProjectFile(bad, path);
    ADD_FAILURE() << "wrote an invalid project";
  } catch (const Error& error) {
    EXPECT_NE(
        std::string(error.what()).find("'" + path + "': not writing an invalid project: field 'polygons[1].vertices'"),
        std::string::npos)
        << error.what();
  }
  EXPECT_EQ(plumb::test::readFile(path), before);

  // A folder that does not exist.
  const std::string nowhere = directory.file("nowhere/room.plumbproj");
  try {
    writeProjectFile(test::sampleProject(), nowhere);
    ADD_FAILURE() << "wrote into a folder that does not exist";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find(nowhere), std::string::npos) << error.what();
  }
  EXPECT_EQ(directory.entryCount(), 1u);
}

// A write that fails in the middle (the disk full: here a file size limit, which binds root too,
// so the test runs in CI) throws and leaves the old project and no temporary file.
TEST(ProjectFile, AWriteThatFailsMidwayLeavesTheOldFile) {
  plumb::test::TempDirectory directory;
  const std::string path = directory.file("room.plumbproj");
  writeProjectFile(test::sampleProject(), path);
  const std::string before = plumb::test::readFile(path);
  ASSERT_GT(before.size(), 64u);
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    ::signal(SIGXFSZ, SIG_IGN);  // a write past the limit fails with EFBIG instead of killing
    const rlimit limit{64, 64};
    if (::setrlimit(RLIMIT_FSIZE, &limit) != 0) _exit(2);
    Project changed = test::sampleProject();
    changed.cloud_path = "elsewhere.plumb";
    try {
      writeProjectFile(changed, path);
    } catch (const Error& error) {
      _exit(std::string(error.what()).find(path) != std::string::npos ? 0 : 3);
    }
    _exit(1);  // wrote past the limit
  }
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 0) << "1: no error; 2: no limit; 3: an error without the file's name";
  EXPECT_EQ(plumb::test::readFile(path), before);
  EXPECT_EQ(directory.entryCount(), 1u);
}

TEST(ProjectFile, ValidationFindsTheFirstProblem) {
  EXPECT_FALSE(findProjectProblem(test::sampleProject()));
  Project project = test::sampleProject();
  project.segments[2].plane.valid = false;
  const auto problem = findProjectProblem(project);
  ASSERT_TRUE(problem);
  EXPECT_EQ(problem->place, "segments[2].plane");
  project = test::sampleProject();
  project.corners[0].position.x() = std::nan("");
  ASSERT_TRUE(findProjectProblem(project));
  EXPECT_EQ(findProjectProblem(project)->place, "corners[0].position");
}

}  // namespace
}  // namespace plumb::cad
