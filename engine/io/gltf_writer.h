#pragma once
// A writer of glTF 2.0 binary files (.glb) for what Plumb exports or shows to other tools:
// triangle meshes (polygons, outlines filled), line sets (edges) and point sets (corners, seeds).
//
// Precision: glTF stores positions as 32-bit floats, which at UTM coordinates (x ~ 5e5, y ~ 5e6)
// would round to half a metre. So the scene has one root node, named kGltfRootNodeName, whose
// translation is a world origin (the centre of the bounding box of every position, rounded to
// whole metres, stored exactly as a double in the JSON), and every position is stored relative
// to it, the subtraction done in double. A position d metres from the origin keeps an error below
// d * 6e-8 (half a float ulp): 0.06 mm at 1 km, 0.5 mm at 8 km. A reader reproduces world
// coordinates as root translation + stored position.
//
// Coordinates are written as given (Plumb's world frame, z up); glTF's convention is y up, so a
// viewer that honours it shows the scene lying on its side unless the reader converts.
//
// Layout: node 0 is the root; under it, in the order meshes, lines, points, each element is one
// node with its own mesh, one primitive and one material (baseColorFactor = colour_rgba,
// metallicFactor 0; alphaMode BLEND when alpha < 1; doubleSided for triangle meshes). Triangle
// meshes have POSITION and UNSIGNED_INT indices (mode 4, no normals: viewers compute flat ones);
// lines have two positions per segment, not indexed (mode 1); points one position each (mode 0).
// POSITION accessors carry min and max, as the specification requires. An element with nothing
// to draw (no triangles, segments or positions) is still a named node, without a mesh, because
// the specification forbids empty accessors. An empty name becomes "mesh_<i>", "lines_<i>" or
// "points_<i>" (i indexing its vector).

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace plumb::io {

// World coordinates in double precision throughout; colours are linear RGBA, each in [0, 1].
struct GltfMesh {
  std::string name;
  std::vector<Eigen::Vector3d> positions;
  std::vector<std::array<std::uint32_t, 3>> triangles;  // indices into positions, counter-clockwise
  std::array<float, 4> colour_rgba{0.8f, 0.8f, 0.8f, 1.0f};
};

struct GltfLines {
  std::string name;
  std::vector<std::array<Eigen::Vector3d, 2>> segments;
  std::array<float, 4> colour_rgba{1.0f, 1.0f, 1.0f, 1.0f};
};

struct GltfPoints {
  std::string name;
  std::vector<Eigen::Vector3d> positions;
  std::array<float, 4> colour_rgba{1.0f, 1.0f, 1.0f, 1.0f};
};

struct GltfScene {
  std::vector<GltfMesh> meshes;
  std::vector<GltfLines> lines;
  std::vector<GltfPoints> points;
};

inline constexpr const char* kGltfRootNodeName = "plumb_world_origin";

// Writes `scene` to `path` as one .glb file (one buffer, in its BIN chunk), atomically through
// AtomicFile: on any error nothing appears at `path`. Throws plumb::Error, its message naming the
// path and the element (kind, name and index), for: a position that is not finite or has a coordinate
// beyond 1e9 m; a triangle index not below the mesh's position count; more than
// 2^32 - 1 positions in one mesh; a colour component that is not finite or outside [0, 1]; a
// scene whose data passes the 4 GiB a .glb can hold; a file that cannot be written.
// Memory: the whole file is assembled in memory (about 3 times the float data). Thread-safe for
// distinct paths.
void writeGlb(const GltfScene& scene, const std::string& path);

}  // namespace plumb::io
