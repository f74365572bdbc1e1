#include "engine/io/gltf_writer.h"

#include <gtest/gtest.h>
#include <tiny_gltf.h>

#include <cstring>
#include <string>

#include "engine/core/error.h"
#include "tests/support/temp_directory.h"

namespace plumb::io {
namespace {

constexpr double kWorldTolerance = 1e-4;  // metres: root translation + stored float vs the input double

tinygltf::Model load(const std::string& path) {
  tinygltf::TinyGLTF loader;
  tinygltf::Model model;
  std::string error, warning;
  const bool ok = loader.LoadBinaryFromFile(&model, &error, &warning, path);
  EXPECT_TRUE(ok) << error;
  EXPECT_TRUE(error.empty()) << error;
  EXPECT_TRUE(warning.empty()) << warning;
  return model;
}

// The world coordinates of a POSITION accessor: the root's translation plus each stored float.
// The first byte of an accessor's data in the model's buffer.
const unsigned char* accessorData(const tinygltf::Model& model, const tinygltf::Accessor& accessor) {
  const tinygltf::BufferView& view = model.bufferViews.at(static_cast<std::size_t>(accessor.bufferView));
  const tinygltf::Buffer& buffer = model.buffers.at(static_cast<std::size_t>(view.buffer));
  return buffer.data.data() + view.byteOffset + accessor.byteOffset;
}

std::vector<Eigen::Vector3d> worldPositions(const tinygltf::Model& model, int accessor_index) {
  const tinygltf::Accessor& accessor = model.accessors.at(static_cast<std::size_t>(accessor_index));
  EXPECT_EQ(accessor.componentType, TINYGLTF_COMPONENT_TYPE_FLOAT);
  EXPECT_EQ(accessor.type, TINYGLTF_TYPE_VEC3);
  const unsigned char* data = accessorData(model, accessor);
  const std::vector<double>& t = model.nodes.at(0).translation;
  std::vector<Eigen::Vector3d> result;
  for (std::size_t i = 0; i < accessor.count; ++i) {
    float xyz[3];
    std::memcpy(xyz, data + i * 12, 12);
    result.emplace_back(t[0] + xyz[0], t[1] + xyz[1], t[2] + xyz[2]);
    // min and max must bound the stored values (the specification requires them for POSITION).
    for (std::size_t axis = 0; axis < 3; ++axis) {
      EXPECT_GE(xyz[axis], accessor.minValues.at(axis));
      EXPECT_LE(xyz[axis], accessor.maxValues.at(axis));
    }
  }
  return result;
}

std::vector<std::uint32_t> indices(const tinygltf::Model& model, int accessor_index) {
  const tinygltf::Accessor& accessor = model.accessors.at(static_cast<std::size_t>(accessor_index));
  EXPECT_EQ(accessor.componentType, TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT);
  EXPECT_EQ(accessor.type, TINYGLTF_TYPE_SCALAR);
  std::vector<std::uint32_t> result(accessor.count);
  std::memcpy(result.data(), accessorData(model, accessor), accessor.count * 4);
  return result;
}

void expectNear(const std::vector<Eigen::Vector3d>& got, const std::vector<Eigen::Vector3d>& want) {
  ASSERT_EQ(got.size(), want.size());
  for (std::size_t i = 0; i < got.size(); ++i) {
    EXPECT_LT((got[i] - want[i]).cwiseAbs().maxCoeff(), kWorldTolerance) << i << ": " << got[i].transpose();
  }
}

// A 1 m square at UTM coordinates as two triangles, an edge along its top, two corner points:
//
//   3 +-----+ 2     lines: 3 -> 2 (and a second segment 0.5 m above it)
//     |   / |       points: 0 and 2
//     | /   |
//   0 +-----+ 1     x = 512000 .. 512001, y = 5403000, z = 250 .. 251
GltfScene utmScene() {
  const Eigen::Vector3d p0(512000.0, 5403000.0, 250.0), p1(512001.0, 5403000.0, 250.0);
  const Eigen::Vector3d p2(512001.0, 5403000.0, 251.0), p3(512000.0, 5403000.0, 251.0);
  GltfScene scene;
  scene.meshes.push_back({"wall", {p0, p1, p2, p3}, {{{0, 1, 2}}, {{0, 2, 3}}}, {0.8f, 0.6f, 0.2f, 0.5f}});
  scene.lines.push_back(
      {"edges", {{p3, p2}, {p3 + Eigen::Vector3d(0, 0, 0.5), p2 + Eigen::Vector3d(0.0003, 0, 0.5)}}, {1, 0, 0, 1}});
  scene.points.push_back({"corners", {p0 + Eigen::Vector3d(0.0001, 0.0002, 0.0003), p2}, {0, 0, 1, 1}});
  return scene;
}

TEST(GltfWriter, KeepsUtmCoordinatesThroughTheRootTranslation) {
  test::TempDirectory directory;
  const std::string path = directory.file("scene.glb");
  const GltfScene scene = utmScene();
  writeGlb(scene, path);
  EXPECT_EQ(directory.entryCount(), 1u);  // no temporary file left
  EXPECT_EQ(test::readFile(path).substr(0, 4), "glTF");

  const tinygltf::Model model = load(path);
  EXPECT_EQ(model.asset.version, "2.0");
  ASSERT_EQ(model.scenes.size(), 1u);
  ASSERT_EQ(model.scenes[0].nodes, std::vector<int>{0});
  ASSERT_EQ(model.nodes.size(), 4u);
  const tinygltf::Node& root = model.nodes[0];
  EXPECT_EQ(root.name, kGltfRootNodeName);
  EXPECT_EQ(root.children, (std::vector<int>{1, 2, 3}));
  ASSERT_EQ(root.translation.size(), 3u);
  // The centre of the bounding box, whole metres.
  EXPECT_EQ(root.translation[0], std::round(512000.50015));
  EXPECT_EQ(root.translation[1], 5403000.0);
  EXPECT_EQ(root.translation[2], std::round(250.75));
  ASSERT_EQ(model.meshes.size(), 3u);

  // The wall: two indexed triangles, double-sided, blended (alpha 0.5).
  const tinygltf::Node& wall = model.nodes[1];
  EXPECT_EQ(wall.name, "wall");
  const tinygltf::Primitive& triangles = model.meshes.at(static_cast<std::size_t>(wall.mesh)).primitives.at(0);
  EXPECT_EQ(triangles.mode, TINYGLTF_MODE_TRIANGLES);
  expectNear(worldPositions(model, triangles.attributes.at("POSITION")), scene.meshes[0].positions);
  EXPECT_EQ(indices(model, triangles.indices), (std::vector<std::uint32_t>{0, 1, 2, 0, 2, 3}));
  const tinygltf::Material& wall_material = model.materials.at(static_cast<std::size_t>(triangles.material));
  EXPECT_TRUE(wall_material.doubleSided);
  EXPECT_EQ(wall_material.alphaMode, "BLEND");
  EXPECT_EQ(wall_material.pbrMetallicRoughness.baseColorFactor,
            (std::vector<double>{0.8f, 0.6f, 0.2f, 0.5f}));  // the floats, widened

  // The edges: two segments, four positions, mode 1, not indexed.
  const tinygltf::Node& edges = model.nodes[2];
  EXPECT_EQ(edges.name, "edges");
  const tinygltf::Primitive& lines = model.meshes.at(static_cast<std::size_t>(edges.mesh)).primitives.at(0);
  EXPECT_EQ(lines.mode, TINYGLTF_MODE_LINE);
  EXPECT_EQ(lines.indices, -1);
  std::vector<Eigen::Vector3d> ends;
  for (const auto& segment : scene.lines[0].segments) ends.insert(ends.end(), segment.begin(), segment.end());
  expectNear(worldPositions(model, lines.attributes.at("POSITION")), ends);
  const tinygltf::Material& line_material = model.materials.at(static_cast<std::size_t>(lines.material));
  EXPECT_EQ(line_material.alphaMode, "OPAQUE");
  EXPECT_FALSE(line_material.doubleSided);

  // The corners: two points, mode 0; the 0.1 mm offsets survive.
  const tinygltf::Node& corners = model.nodes[3];
  EXPECT_EQ(corners.name, "corners");
  const tinygltf::Primitive& points = model.meshes.at(static_cast<std::size_t>(corners.mesh)).primitives.at(0);
  EXPECT_EQ(points.mode, TINYGLTF_MODE_POINTS);
  const std::vector<Eigen::Vector3d> corner_positions = worldPositions(model, points.attributes.at("POSITION"));
  expectNear(corner_positions, scene.points[0].positions);
  EXPECT_NEAR(corner_positions[0].x() - 512000.0, 0.0001, 1e-5);
}

TEST(GltfWriter, AnEmptySceneIsAValidFile) {
  test::TempDirectory directory;
  const std::string path = directory.file("empty.glb");
  writeGlb(GltfScene{}, path);
  const tinygltf::Model model = load(path);
  ASSERT_EQ(model.nodes.size(), 1u);
  EXPECT_EQ(model.nodes[0].name, kGltfRootNodeName);
  EXPECT_TRUE(model.nodes[0].children.empty());
  EXPECT_TRUE(model.meshes.empty());
  EXPECT_TRUE(model.buffers.empty());
}

TEST(GltfWriter, ElementsWithoutGeometryBecomeNamedNodesWithoutMeshes) {
  test::TempDirectory directory;
  const std::string path = directory.file("hollow.glb");
  GltfScene scene = utmScene();
  scene.meshes.push_back({"", {Eigen::Vector3d(512000.0, 5403000.0, 250.0)}, {}, {1, 1, 1, 1}});
  scene.points.push_back({"", {}, {1, 1, 1, 1}});
  writeGlb(scene, path);
  const tinygltf::Model model = load(path);
  ASSERT_EQ(model.nodes.size(), 6u);
  EXPECT_EQ(model.nodes[2].name, "mesh_1");
  EXPECT_EQ(model.nodes[2].mesh, -1);
  EXPECT_EQ(model.nodes[5].name, "points_1");
  EXPECT_EQ(model.nodes[5].mesh, -1);
  EXPECT_EQ(model.meshes.size(), 3u);
}

void expectThrowsAndLeavesNothing(const GltfScene& scene, const std::vector<std::string>& parts) {
  test::TempDirectory directory;
  const std::string path = directory.file("bad.glb");
  try {
    writeGlb(scene, path);
    ADD_FAILURE() << "no error";
  } catch (const Error& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find(path), std::string::npos) << message;
    for (const auto& part : parts) EXPECT_NE(message.find(part), std::string::npos) << message << "\nlacks: " << part;
  }
  EXPECT_EQ(directory.entryCount(), 0u);
}

TEST(GltfWriter, RejectsBadInputNamingTheElementAndLeavesNoFile) {
  GltfScene scene = utmScene();
  scene.meshes[0].triangles[1][2] = 4;  // one past the four positions
  expectThrowsAndLeavesNothing(scene, {"mesh 'wall' (meshes[0])", "triangle 1", "position 4", "4 positions"});

  scene = utmScene();
  scene.points[0].positions[1].y() = std::nan("");
  expectThrowsAndLeavesNothing(scene, {"points 'corners' (points[0])", "position 1", "not finite"});

  scene = utmScene();
  scene.lines[0].segments[1][0].z() = INFINITY;
  expectThrowsAndLeavesNothing(scene, {"lines 'edges' (lines[0])", "position 2", "not finite"});

  scene = utmScene();
  scene.meshes[0].colour_rgba[3] = 1.5f;
  expectThrowsAndLeavesNothing(scene, {"mesh 'wall'", "colour_rgba"});

  scene = utmScene();
  scene.points[0].positions[0].x() = 1e300;  // finite, but its offset from any origin would overflow a float
  expectThrowsAndLeavesNothing(scene, {"points 'corners'", "position 0", "beyond 1e9 m"});
}

TEST(GltfWriter, ReplacesAnExistingFileWhole) {
  test::TempDirectory directory;
  const std::string path = directory.write("scene.glb", "old contents");
  writeGlb(utmScene(), path);
  EXPECT_EQ(load(path).nodes.size(), 4u);
}

}  // namespace
}  // namespace plumb::io
