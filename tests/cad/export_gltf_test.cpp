#include "cad/export_gltf.h"

#include <gtest/gtest.h>
#include <tiny_gltf.h>

#include <cstring>

#include "cad/polygon_mesh.h"
#include "engine/io/gltf_writer.h"
#include "tests/cad/sample_project.h"
#include "tests/support/temp_directory.h"

namespace plumb::cad {
namespace {

// glTF holds floats about the root translation: 6e-8 of the distance, well below this a few
// metres from it.
constexpr double kWorldTolerance = 1e-5;

tinygltf::Model load(const std::string& path) {
  tinygltf::TinyGLTF loader;
  tinygltf::Model model;
  std::string error, warning;
  EXPECT_TRUE(loader.LoadBinaryFromFile(&model, &error, &warning, path)) << error;
  EXPECT_TRUE(warning.empty()) << warning;
  return model;
}

const tinygltf::Primitive& primitiveOf(const tinygltf::Model& model, const tinygltf::Node& node) {
  return model.meshes.at(static_cast<std::size_t>(node.mesh)).primitives.at(0);
}

// The world positions of a primitive: the root's translation plus each stored float.
std::vector<Eigen::Vector3d> worldPositions(const tinygltf::Model& model, const tinygltf::Primitive& primitive) {
  const tinygltf::Accessor& accessor =
      model.accessors.at(static_cast<std::size_t>(primitive.attributes.at("POSITION")));
  const tinygltf::BufferView& view = model.bufferViews.at(static_cast<std::size_t>(accessor.bufferView));
  const unsigned char* data = model.buffers.at(0).data.data() + view.byteOffset + accessor.byteOffset;
  const std::vector<double>& t = model.nodes.at(0).translation;
  std::vector<Eigen::Vector3d> positions;
  for (std::size_t i = 0; i < accessor.count; ++i) {
    float xyz[3];
    std::memcpy(xyz, data + 12 * i, 12);
    positions.emplace_back(t[0] + xyz[0], t[1] + xyz[1], t[2] + xyz[2]);
  }
  return positions;
}

std::size_t indexCount(const tinygltf::Model& model, const tinygltf::Primitive& primitive) {
  return model.accessors.at(static_cast<std::size_t>(primitive.indices)).count;
}

void expectPositions(const std::vector<Eigen::Vector3d>& got, const std::vector<Eigen::Vector3d>& want,
                     const std::string& what) {
  ASSERT_EQ(got.size(), want.size()) << what;
  for (std::size_t i = 0; i < got.size(); ++i) {
    EXPECT_LT((got[i] - want[i]).cwiseAbs().maxCoeff(), kWorldTolerance) << what << " " << i;
  }
}

TEST(ExportGltf, NamedNodesPerItemAtWorldCoordinates) {
  plumb::test::TempDirectory directory;
  const Project project = test::sampleProject();
  const std::string path = directory.file("room.glb");
  exportGltf(project, path);
  EXPECT_EQ(directory.entryCount(), 1u);
  const tinygltf::Model model = load(path);

  ASSERT_EQ(model.nodes.size(), 1u + 3 + 3 + 3 + 2);
  EXPECT_EQ(model.nodes[0].name, io::kGltfRootNodeName);
  std::vector<std::string> names;
  for (std::size_t n = 1; n < model.nodes.size(); ++n) names.push_back(model.nodes[n].name);
  EXPECT_EQ(names,
            (std::vector<std::string>{"window 1", "L", "polygon 42", "floor", "wall x", "segment 12", "floor | wall x",
                                      "edge 21", "edge 22", "corner \"A\", north", "corner 31"}));

  for (std::size_t i = 0; i < project.polygons.size(); ++i) {
    const TriangleMesh mesh = prismMesh(project.polygons[i]);
    const tinygltf::Primitive& primitive = primitiveOf(model, model.nodes[1 + i]);
    EXPECT_EQ(primitive.mode, TINYGLTF_MODE_TRIANGLES);
    expectPositions(worldPositions(model, primitive), mesh.positions, names[i]);
    EXPECT_EQ(indexCount(model, primitive), 3 * mesh.triangles.size());
  }
  for (std::size_t i = 0; i < project.segments.size(); ++i) {
    const tinygltf::Primitive& primitive = primitiveOf(model, model.nodes[4 + i]);
    expectPositions(worldPositions(model, primitive), outlineMesh(project.segments[i].outline).positions, names[3 + i]);
    const tinygltf::Material& material = model.materials.at(static_cast<std::size_t>(primitive.material));
    EXPECT_EQ(material.pbrMetallicRoughness.baseColorFactor.at(3), 0.5) << "outlines are translucent";
    EXPECT_EQ(material.alphaMode, "BLEND");
  }
  for (std::size_t i = 0; i < project.edges.size(); ++i) {
    const tinygltf::Primitive& primitive = primitiveOf(model, model.nodes[7 + i]);
    EXPECT_EQ(primitive.mode, TINYGLTF_MODE_LINE);
    expectPositions(worldPositions(model, primitive), {project.edges[i].start, project.edges[i].end}, names[6 + i]);
  }
  for (std::size_t i = 0; i < project.corners.size(); ++i) {
    const tinygltf::Primitive& primitive = primitiveOf(model, model.nodes[10 + i]);
    EXPECT_EQ(primitive.mode, TINYGLTF_MODE_POINTS);
    expectPositions(worldPositions(model, primitive), {project.corners[i].position}, names[9 + i]);
  }
}

}  // namespace
}  // namespace plumb::cad
