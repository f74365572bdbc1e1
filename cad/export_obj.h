#pragma once
// Wavefront OBJ export of a project, for tools that read meshes (Blender, MeshLab, CloudCompare,
// most CAD packages). World coordinates in metres, z up, each number with every digit of its
// double (cad/number_text.h): UTM coordinates keep far better than 0.01 mm.
//
// One object ("o NAME") per item, in the order polygons (prisms included), segments, edges,
// corners: a polygon's or prism's prismMesh and a segment's outlineMesh as "v" and "f" (1-based
// indices into one vertex list for the whole file, triangles counter-clockwise seen from outside),
// an edge as two "v" and one "l", a corner as one "v" and one "p". NAME is the item's name (or
// "polygon 12", "segment 3", "edge 7", "corner 9" without one) with every space, control
// character and '#' replaced by '_'. No normals, no texture coordinates, no materials.

#include <string>

#include "cad/project.h"

namespace plumb {
class AtomicFile;
}

namespace plumb::cad {

// Writes `project` to `out` without committing it (the caller finishes and commits, so that
// several outputs can appear together). Throws plumb::Error naming out.path() when the project
// breaks a rule of findProjectProblem or the write fails.
void exportObj(const Project& project, AtomicFile& out);

// Writes `project` to `path` atomically: on any error nothing appears there. Throws as above.
void exportObj(const Project& project, const std::string& path);

}  // namespace plumb::cad
