#include "cad/export_obj.h"

#include <gtest/gtest.h>

#include <sstream>

#include "cad/polygon_mesh.h"
#include "engine/core/error.h"
#include "tests/cad/sample_project.h"
#include "tests/support/temp_directory.h"

namespace plumb::cad {
namespace {

constexpr double kCoordinateTolerance = 1e-5;  // metres: 0.01 mm, what a survey needs

// What a small OBJ reader sees: objects with their own vertices, faces, lines and points, the
// indices made 0-based and relative to the file's vertex list.
struct ObjObject {
  std::string name;
  std::vector<std::array<std::size_t, 3>> faces;
  std::vector<std::array<std::size_t, 2>> lines;
  std::vector<std::size_t> points;
};
struct ObjFile {
  std::vector<Eigen::Vector3d> vertices;
  std::vector<ObjObject> objects;
};

ObjFile parseObj(const std::string& text) {
  ObjFile obj;
  std::istringstream lines(text);
  std::string line;
  const auto index = [&obj](const std::string& word) {
    const std::size_t one_based = std::stoul(word);
    EXPECT_GE(one_based, 1u);
    EXPECT_LE(one_based, obj.vertices.size()) << "an index ahead of its vertex";
    return one_based - 1;
  };
  while (std::getline(lines, line)) {
    std::istringstream words(line);
    std::string kind;
    words >> kind;
    if (kind.empty() || kind[0] == '#') continue;
    if (kind == "o") {
      obj.objects.push_back({});
      words >> obj.objects.back().name;
      std::string rest;
      EXPECT_FALSE(words >> rest) << "a name with a space: " << line;
      continue;
    }
    if (kind == "v") {
      std::string x, y, z;
      words >> x >> y >> z;
      obj.vertices.emplace_back(std::stod(x), std::stod(y), std::stod(z));
      continue;
    }
    EXPECT_FALSE(obj.objects.empty()) << "geometry before the first object: " << line;
    if (obj.objects.empty()) continue;
    ObjObject& object = obj.objects.back();
    std::string a, b, c;
    if (kind == "f") {
      words >> a >> b >> c;
      object.faces.push_back({index(a), index(b), index(c)});
    } else if (kind == "l") {
      words >> a >> b;
      object.lines.push_back({index(a), index(b)});
    } else if (kind == "p") {
      words >> a;
      object.points.push_back(index(a));
    } else {
      ADD_FAILURE() << "unexpected line: " << line;
    }
  }
  return obj;
}

void expectNear(const Eigen::Vector3d& got, const Eigen::Vector3d& want, const std::string& what) {
  EXPECT_LT((got - want).cwiseAbs().maxCoeff(), kCoordinateTolerance) << what << ": " << got.transpose();
}

// The triangles of `object` as positions, against those of `mesh`.
void expectMesh(const ObjFile& obj, const ObjObject& object, const TriangleMesh& mesh) {
  ASSERT_EQ(object.faces.size(), mesh.triangles.size()) << object.name;
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    for (std::size_t k = 0; k < 3; ++k) {
      expectNear(obj.vertices[object.faces[t][k]], mesh.positions[mesh.triangles[t][k]], object.name);
    }
  }
}

TEST(ExportObj, OneObjectPerItemInWorldCoordinates) {
  plumb::test::TempDirectory directory;
  const Project project = test::sampleProject();
  const std::string path = directory.file("room.obj");
  exportObj(project, path);
  EXPECT_EQ(directory.entryCount(), 1u);
  const ObjFile obj = parseObj(plumb::test::readFile(path));

  std::vector<std::string> names;
  for (const ObjObject& object : obj.objects) names.push_back(object.name);
  EXPECT_EQ(names,
            (std::vector<std::string>{"window_1", "L", "polygon_42", "floor", "wall_x", "segment_12", "floor_|_wall_x",
                                      "edge_21", "edge_22", "corner_\"A\",_north", "corner_31"}));
  ASSERT_EQ(obj.objects.size(), 11u);
  std::size_t vertices = 0, faces = 0;
  for (std::size_t i = 0; i < project.polygons.size(); ++i) {
    const TriangleMesh mesh = prismMesh(project.polygons[i]);
    expectMesh(obj, obj.objects[i], mesh);
    vertices += mesh.positions.size();
    faces += mesh.triangles.size();
  }
  EXPECT_EQ(obj.objects[2].faces.size(), 12u) << "the box: 2 + 2 caps, 8 sides";
  for (std::size_t i = 0; i < project.segments.size(); ++i) {
    const TriangleMesh mesh = outlineMesh(project.segments[i].outline);
    expectMesh(obj, obj.objects[3 + i], mesh);
    vertices += mesh.positions.size();
    faces += mesh.triangles.size();
  }
  for (std::size_t i = 0; i < project.edges.size(); ++i) {
    const ObjObject& object = obj.objects[6 + i];
    ASSERT_EQ(object.lines.size(), 1u);
    expectNear(obj.vertices[object.lines[0][0]], project.edges[i].start, object.name);
    expectNear(obj.vertices[object.lines[0][1]], project.edges[i].end, object.name);
  }
  for (std::size_t i = 0; i < project.corners.size(); ++i) {
    const ObjObject& object = obj.objects[9 + i];
    ASSERT_EQ(object.points.size(), 1u);
    expectNear(obj.vertices[object.points[0]], project.corners[i].position, object.name);
  }
  EXPECT_EQ(obj.vertices.size(), vertices + 2 * project.edges.size() + project.corners.size());
  std::size_t all_faces = 0;
  for (const ObjObject& object : obj.objects) all_faces += object.faces.size();
  EXPECT_EQ(all_faces, faces);
  // Shortest round-trip digits: the UTM coordinate comes back as the same double.
  EXPECT_EQ(obj.vertices[0], project.polygons[0].vertices[0]);
}

TEST(ExportObj, RefusesAnInvalidProjectAndLeavesNothing) {
  plumb::test::TempDirectory directory;
  Project project = test::sampleProject();
  project.polygons[1].vertices[2] = project.polygons[1].vertices[1];
  const std::string path = directory.file("room.obj");
  try {
    exportObj(project, path);
    ADD_FAILURE() << "exported an invalid project";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what())
                  .find("'" + path + "': not exporting an invalid project: field 'polygons[1].vertices'"),
              std::string::npos)
        << error.what();
  }
  EXPECT_EQ(directory.entryCount(), 0u);
}

}  // namespace
}  // namespace plumb::cad
