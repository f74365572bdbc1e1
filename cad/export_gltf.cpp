#include "cad/export_gltf.h"

#include <stdlib.h>

#include <cerrno>
#include <filesystem>

#include "cad/item_name.h"
#include "cad/polygon_mesh.h"
#include "cad/project_validation.h"
#include "cad/text_file.h"
#include "engine/core/atomic_file.h"
#include "engine/core/error.h"
#include "engine/io/gltf_writer.h"

namespace plumb::cad {
namespace {

constexpr std::array<float, 4> kPolygonColour{0.95f, 0.75f, 0.20f, 1.0f};
constexpr std::array<float, 4> kPrismColour{0.45f, 0.55f, 0.95f, 1.0f};
constexpr std::array<float, 4> kSegmentColour{0.25f, 0.60f, 0.90f, 0.5f};
constexpr std::array<float, 4> kEdgeColour{1.0f, 1.0f, 1.0f, 1.0f};
constexpr std::array<float, 4> kCornerColour{0.90f, 0.10f, 0.10f, 1.0f};

io::GltfMesh gltfMesh(std::string name, TriangleMesh mesh, const std::array<float, 4>& colour) {
  return {std::move(name), std::move(mesh.positions), std::move(mesh.triangles), colour};
}

io::GltfScene gltfScene(const Project& project) {
  io::GltfScene scene;
  for (const Polygon& polygon : project.polygons) {
    scene.meshes.push_back(gltfMesh(itemName(polygon.name, "polygon", polygon.id), prismMesh(polygon),
                                    polygon.isPrism() ? kPrismColour : kPolygonColour));
  }
  for (const Segment& segment : project.segments) {
    scene.meshes.push_back(
        gltfMesh(itemName(segment.name, "segment", segment.id), outlineMesh(segment.outline), kSegmentColour));
  }
  for (const Edge& edge : project.edges) {
    scene.lines.push_back({itemName(edge.name, "edge", edge.id), {{edge.start, edge.end}}, kEdgeColour});
  }
  for (const Corner& corner : project.corners) {
    scene.points.push_back({itemName(corner.name, "corner", corner.id), {corner.position}, kCornerColour});
  }
  return scene;
}

// A folder of its own under the temporary directory, removed with its content.
class StagingFolder {
 public:
  explicit StagingFolder(const std::string& for_path) {
    std::error_code error;
    const std::filesystem::path base = std::filesystem::temp_directory_path(error);
    std::string pattern = ((error ? std::filesystem::path("/tmp") : base) / "plumb-export-XXXXXX").string();
    if (::mkdtemp(pattern.data()) == nullptr) {
      throw fileError(for_path, "cannot create a temporary folder to assemble the glTF binary in (" + pattern + ": " +
                                    systemErrorText(errno) + "); set TMPDIR to a writable folder");
    }
    path_ = pattern;
  }
  ~StagingFolder() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  StagingFolder(const StagingFolder&) = delete;
  StagingFolder& operator=(const StagingFolder&) = delete;

  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

}  // namespace

void exportGltf(const Project& project, AtomicFile& out) {
  validateProject(project, out.path(), "not exporting an invalid project");
  const io::GltfScene scene = gltfScene(project);
  const StagingFolder staging(out.path());
  const std::string staged = (staging.path() / "scene.glb").string();
  try {
    io::writeGlb(scene, staged);
  } catch (const Error& error) {
    // writeGlb names the staged file; the user knows only the output.
    std::string what = error.what();
    const std::string prefix = "'" + staged + "': ";
    if (what.starts_with(prefix)) what.erase(0, prefix.size());
    throw fileError(out.path(), what);
  }
  const std::string bytes = readTextFile(staged, "glTF binary");
  out.write(bytes.data(), bytes.size());
}

void exportGltf(const Project& project, const std::string& path) {
  validateProject(project, path, "not exporting an invalid project");
  io::writeGlb(gltfScene(project), path);
}

}  // namespace plumb::cad
