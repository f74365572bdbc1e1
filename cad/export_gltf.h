#pragma once
// glTF 2.0 binary (.glb) export of a project through io::writeGlb (engine/io/gltf_writer.h), which
// keeps UTM precision with a root translation. One named node per item, world coordinates:
// - polygons and prisms: their prismMesh as triangle meshes, opaque (polygons amber, prisms blue);
// - segments: their outlineMesh, translucent blue (alpha 0.5), so the cloud shows through;
// - edges: one line each, white; corners: one point each, red.
// A node is named after its item, or "polygon 12", "segment 3", "edge 7", "corner 9" for an item
// without a name. A segment with an empty outline is a node without a mesh.

#include <string>

#include "cad/project.h"

namespace plumb {
class AtomicFile;
}

namespace plumb::cad {

// Writes `project` to `out` without committing it. io::writeGlb writes only whole files of its
// own, so the binary is assembled in a private folder under the system's temporary directory
// (TMPDIR), copied into `out` and removed. Throws plumb::Error naming out.path() when the project
// breaks a rule of findProjectProblem, a coordinate is beyond what glTF holds (1e9 m), or a write
// fails. Memory: about four times the file's size.
void exportGltf(const Project& project, AtomicFile& out);

// Writes `project` to `path` atomically (io::writeGlb directly): on any error nothing appears
// there. Throws as above.
void exportGltf(const Project& project, const std::string& path);

}  // namespace plumb::cad
