#pragma once
// The viewer's scene as a cad::Project and back: what Save, the autosave and `plumb view
// --project` read and write. Items get ids in the order of their kinds (groups, segments, edges,
// corners, polygons), numbered from 1; references between items follow them.

#include <optional>
#include <string>

#include "cad/project.h"
#include "engine/view/camera.h"

namespace plumb::ecs {
class Registry;
}

namespace plumb::viewer {

class SceneState;

// The document in `registry`: every finished segment (a growing one is not part of it), edge,
// corner, polygon and group. References to items no longer there (a polygon's deleted plane)
// become kNoItem.
cad::Project projectOf(const ecs::Registry& registry, std::string cloud_path, std::optional<view::Camera> camera);

// Replaces the scene's items with the project's, unrecorded (the history starts empty), and
// continues the "Segment N" (...) numbering after the highest N in the project's names.
void loadProject(const cad::Project& project, SceneState& scene);

// A number that changes whenever the document in `registry` does (for "unsaved changes").
std::uint64_t documentVersion(const ecs::Registry& registry);

}  // namespace plumb::viewer
