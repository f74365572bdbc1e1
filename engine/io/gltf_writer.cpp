// glTF 2.0 binary writer. Steps:
//   1. Validate every element (finite positions, indices in range, colours in [0, 1]) before any
//      output exists, so that errors name the element and leave nothing behind.
//   2. Choose the world origin: the centre of the bounding box of all positions, whole metres.
//   3. Pack positions (floats relative to the origin) and indices into one buffer, one buffer view
//      and accessor per array, and build the node tree under the root node.
//   4. Serialise to memory with tinygltf (GLB: JSON chunk + BIN chunk) and write it atomically.
//
// tinygltf comes from Debian as a shared library (libtinygltf.so, built with its image support),
// so this file includes only its declarations: no TINYGLTF_IMPLEMENTATION here, and none of the
// TINYGLTF_NO_* macros, which would change the class's default members against the library's.

#include "engine/io/gltf_writer.h"

#include <tiny_gltf.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <sstream>
#include <string_view>

#include "engine/core/atomic_file.h"
#include "engine/core/error.h"

namespace plumb::io {
namespace {

// The .glb header stores the file length in 32 bits.
constexpr std::uint64_t kMaxGlbBytes = std::numeric_limits<std::uint32_t>::max();
// Larger coordinates are mistakes (ECEF coordinates stay below 7e6 m); the bound keeps every
// offset from the origin far inside the range of a float.
constexpr double kMaxCoordinate = 1e9;
// Room kept for the GLB header, the chunk headers and the JSON when checking kMaxGlbBytes.
constexpr std::uint64_t kJsonReserveBytes = std::uint64_t{64} << 20;

// "mesh 'roof' (meshes[2])": how errors name an element.
std::string elementLabel(std::string_view kind, std::string_view vector, std::size_t index, const std::string& name) {
  return std::string(kind) + " '" + name + "' (" + std::string(vector) + "[" + std::to_string(index) + "])";
}

std::string nodeName(std::string_view prefix, std::size_t index, const std::string& name) {
  return name.empty() ? std::string(prefix) + "_" + std::to_string(index) : name;
}

class SceneChecker {
 public:
  explicit SceneChecker(const std::string& path) : path_(path) {}

  void colour(const std::string& label, const std::array<float, 4>& rgba) const {
    for (const float c : rgba) {
      if (!std::isfinite(c) || c < 0.0f || c > 1.0f) {
        throw fileError(path_, label + ": colour_rgba components must lie in [0, 1]");
      }
    }
  }

  void position(const std::string& label, const Eigen::Vector3d& p, std::size_t index) {
    if (!p.allFinite()) {
      throw fileError(path_, label + ": position " + std::to_string(index) + " is not finite");
    }
    if (p.cwiseAbs().maxCoeff() > kMaxCoordinate) {
      throw fileError(path_, label + ": position " + std::to_string(index) +
                                 " has a coordinate beyond 1e9 m (not a world coordinate on Earth)");
    }
    min_ = min_.cwiseMin(p);
    max_ = max_.cwiseMax(p);
    any_ = true;
  }

  void addBytes(std::uint64_t bytes) { bytes_ += bytes; }

  void checkSize() const {
    if (bytes_ + kJsonReserveBytes > kMaxGlbBytes) {
      throw fileError(path_, "the scene needs " + std::to_string(bytes_) +
                                 " bytes of geometry, more than a .glb file can hold (4 GiB); split it");
    }
  }

  // Step 2: the centre of the bounding box, rounded to whole metres so that it prints exactly.
  Eigen::Vector3d origin() const {
    if (!any_) return Eigen::Vector3d::Zero();
    return ((min_ + max_) * 0.5).array().round().matrix();
  }

 private:
  const std::string& path_;
  Eigen::Vector3d min_ = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector3d max_ = Eigen::Vector3d::Constant(-std::numeric_limits<double>::infinity());
  bool any_ = false;
  std::uint64_t bytes_ = 0;
};

tinygltf::Primitive primitive(int positions, int indices, int material, int mode) {
  tinygltf::Primitive result;
  result.attributes["POSITION"] = positions;
  result.indices = indices;
  result.material = material;
  result.mode = mode;
  return result;
}

// Step 3: the model under construction, with its single buffer.
class ModelBuilder {
 public:
  explicit ModelBuilder(const Eigen::Vector3d& origin) : origin_(origin) {
    model_.asset.version = "2.0";
    model_.asset.generator = "Plumb";
    tinygltf::Node root;
    root.name = kGltfRootNodeName;
    root.translation = {origin.x(), origin.y(), origin.z()};
    model_.nodes.push_back(std::move(root));
    tinygltf::Scene scene;
    scene.nodes.push_back(0);
    model_.scenes.push_back(std::move(scene));
    model_.defaultScene = 0;
  }

  // Appends a VEC3 FLOAT accessor of `positions` relative to the origin, with min and max.
  int addPositions(const std::vector<Eigen::Vector3d>& positions) {
    std::vector<float> values;
    values.reserve(positions.size() * 3);
    std::array<double, 3> low{}, high{};
    low.fill(std::numeric_limits<double>::infinity());
    high.fill(-std::numeric_limits<double>::infinity());
    for (std::size_t i = 0; i < positions.size(); ++i) {
      const Eigen::Vector3d relative = positions[i] - origin_;
      for (int axis = 0; axis < 3; ++axis) {
        const float value = static_cast<float>(relative[axis]);
        values.push_back(value);
        // The specification wants the bounds of the stored values, so take them after rounding.
        const auto a = static_cast<std::size_t>(axis);
        low[a] = std::min(low[a], static_cast<double>(value));
        high[a] = std::max(high[a], static_cast<double>(value));
      }
    }
    tinygltf::Accessor accessor;
    accessor.bufferView = addView(values.data(), values.size() * sizeof(float), TINYGLTF_TARGET_ARRAY_BUFFER);
    accessor.componentType = TINYGLTF_COMPONENT_TYPE_FLOAT;
    accessor.type = TINYGLTF_TYPE_VEC3;
    accessor.count = positions.size();
    accessor.minValues.assign(low.begin(), low.end());
    accessor.maxValues.assign(high.begin(), high.end());
    model_.accessors.push_back(std::move(accessor));
    return static_cast<int>(model_.accessors.size() - 1);
  }

  int addIndices(const std::vector<std::array<std::uint32_t, 3>>& triangles) {
    tinygltf::Accessor accessor;
    accessor.bufferView =
        addView(triangles.data(), triangles.size() * sizeof(triangles[0]), TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
    accessor.componentType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
    accessor.type = TINYGLTF_TYPE_SCALAR;
    accessor.count = triangles.size() * 3;
    model_.accessors.push_back(std::move(accessor));
    return static_cast<int>(model_.accessors.size() - 1);
  }

  int addMaterial(const std::string& name, const std::array<float, 4>& rgba, bool double_sided) {
    tinygltf::Material material;
    material.name = name;
    material.pbrMetallicRoughness.baseColorFactor.assign(rgba.begin(), rgba.end());
    // Survey geometry is not metal; metallic 1 (the default) renders it black without an environment.
    material.pbrMetallicRoughness.metallicFactor = 0.0;
    material.pbrMetallicRoughness.roughnessFactor = 1.0;
    material.alphaMode = rgba[3] < 1.0f ? "BLEND" : "OPAQUE";
    material.doubleSided = double_sided;
    model_.materials.push_back(std::move(material));
    return static_cast<int>(model_.materials.size() - 1);
  }

  // A child of the root holding one primitive of `positions` (indexed by `triangles` where not
  // null) in its own material. An element without geometry (no triangles, or no positions) is
  // still a node, without a mesh, so that every element of the scene keeps its name.
  void addElement(const std::string& name, const std::vector<Eigen::Vector3d>& positions,
                  const std::vector<std::array<std::uint32_t, 3>>* triangles, const std::array<float, 4>& rgba,
                  bool double_sided, int mode) {
    if (triangles ? triangles->empty() : positions.empty()) {
      addNode(name, nullptr);
      return;
    }
    const int position_accessor = addPositions(positions);
    const int index_accessor = triangles ? addIndices(*triangles) : -1;
    const int material = addMaterial(name, rgba, double_sided);
    const tinygltf::Primitive element = primitive(position_accessor, index_accessor, material, mode);
    addNode(name, &element);
  }

  // A child of the root; without a mesh when `primitive` is null.
  void addNode(const std::string& name, const tinygltf::Primitive* primitive) {
    tinygltf::Node node;
    node.name = name;
    if (primitive != nullptr) {
      tinygltf::Mesh mesh;
      mesh.name = name;
      mesh.primitives.push_back(*primitive);
      model_.meshes.push_back(std::move(mesh));
      node.mesh = static_cast<int>(model_.meshes.size() - 1);
    }
    model_.nodes.push_back(std::move(node));
    model_.nodes[0].children.push_back(static_cast<int>(model_.nodes.size() - 1));
  }

  tinygltf::Model& finish() {
    // A buffer may not be empty: a scene without geometry has none.
    if (!data_.empty()) {
      tinygltf::Buffer buffer;
      buffer.data = std::move(data_);
      model_.buffers.push_back(std::move(buffer));
    }
    return model_;
  }

 private:
  int addView(const void* bytes, std::size_t size, int target) {
    tinygltf::BufferView view;
    view.buffer = 0;
    view.byteOffset = data_.size();  // every element is 4 bytes wide, so views stay 4-byte aligned
    view.byteLength = size;
    view.target = target;
    const std::size_t at = data_.size();
    data_.resize(at + size);
    std::memcpy(data_.data() + at, bytes, size);
    model_.bufferViews.push_back(std::move(view));
    return static_cast<int>(model_.bufferViews.size() - 1);
  }

  Eigen::Vector3d origin_;
  tinygltf::Model model_;
  std::vector<unsigned char> data_;
};

}  // namespace

void writeGlb(const GltfScene& scene, const std::string& path) {
  // Step 1.
  SceneChecker checker(path);
  for (std::size_t m = 0; m < scene.meshes.size(); ++m) {
    const GltfMesh& mesh = scene.meshes[m];
    const std::string label = elementLabel("mesh", "meshes", m, mesh.name);
    checker.colour(label, mesh.colour_rgba);
    if (mesh.positions.size() > std::numeric_limits<std::uint32_t>::max()) {
      throw fileError(path, label + ": more positions than 32-bit indices can address; split the mesh");
    }
    for (std::size_t i = 0; i < mesh.positions.size(); ++i) checker.position(label, mesh.positions[i], i);
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
      for (const std::uint32_t index : mesh.triangles[t]) {
        if (index >= mesh.positions.size()) {
          throw fileError(path, label + ": triangle " + std::to_string(t) + " refers to position " +
                                    std::to_string(index) + ", but the mesh has " +
                                    std::to_string(mesh.positions.size()) + " positions");
        }
      }
    }
    if (!mesh.triangles.empty()) checker.addBytes(mesh.positions.size() * 12 + mesh.triangles.size() * 12);
  }
  for (std::size_t l = 0; l < scene.lines.size(); ++l) {
    const GltfLines& lines = scene.lines[l];
    const std::string label = elementLabel("lines", "lines", l, lines.name);
    checker.colour(label, lines.colour_rgba);
    for (std::size_t s = 0; s < lines.segments.size(); ++s) {
      checker.position(label, lines.segments[s][0], 2 * s);
      checker.position(label, lines.segments[s][1], 2 * s + 1);
    }
    checker.addBytes(lines.segments.size() * 24);
  }
  for (std::size_t p = 0; p < scene.points.size(); ++p) {
    const GltfPoints& points = scene.points[p];
    const std::string label = elementLabel("points", "points", p, points.name);
    checker.colour(label, points.colour_rgba);
    for (std::size_t i = 0; i < points.positions.size(); ++i) checker.position(label, points.positions[i], i);
    checker.addBytes(points.positions.size() * 12);
  }
  checker.checkSize();

  // Steps 2 and 3.
  ModelBuilder builder(checker.origin());
  for (std::size_t m = 0; m < scene.meshes.size(); ++m) {
    const GltfMesh& mesh = scene.meshes[m];
    builder.addElement(nodeName("mesh", m, mesh.name), mesh.positions, &mesh.triangles, mesh.colour_rgba, true,
                       TINYGLTF_MODE_TRIANGLES);
  }
  for (std::size_t l = 0; l < scene.lines.size(); ++l) {
    const GltfLines& lines = scene.lines[l];
    std::vector<Eigen::Vector3d> ends;
    ends.reserve(lines.segments.size() * 2);
    for (const auto& segment : lines.segments) ends.insert(ends.end(), segment.begin(), segment.end());
    builder.addElement(nodeName("lines", l, lines.name), ends, nullptr, lines.colour_rgba, false, TINYGLTF_MODE_LINE);
  }
  for (std::size_t p = 0; p < scene.points.size(); ++p) {
    const GltfPoints& points = scene.points[p];
    builder.addElement(nodeName("points", p, points.name), points.positions, nullptr, points.colour_rgba, false,
                       TINYGLTF_MODE_POINTS);
  }

  // Step 4. Serialise fully before the output file exists, so a tinygltf failure leaves nothing.
  std::ostringstream stream(std::ios::out | std::ios::binary);
  tinygltf::TinyGLTF gltf;
  if (!gltf.WriteGltfSceneToStream(&builder.finish(), stream, false, true) || !stream) {
    throw fileError(path, "tinygltf could not serialise the scene");
  }
  const std::string bytes = std::move(stream).str();
  AtomicFile file(path);
  file.write(bytes.data(), bytes.size());
  file.commit();
}

}  // namespace plumb::io
