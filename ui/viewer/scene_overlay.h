#pragma once
// What the renderer's overlay pass draws of the scene: segment polygons (translucent, in a
// colour per segment; brighter while growing), their outlines, edges as lines, corners as
// markers, measurements' dimension lines. Rebuilt only when a component type it reads has changed.

#include <cstdint>
#include <memory>

#include "engine/render/overlay_scene.h"

namespace plumb::ecs {
class Registry;
}

namespace plumb::viewer {

class SceneOverlay {
 public:
  // The overlay of `registry` now; the same pointer as last time when nothing it reads changed.
  std::shared_ptr<const render::OverlayScene> update(const ecs::Registry& registry);

 private:
  std::shared_ptr<const render::OverlayScene> overlay_;
  std::uint64_t seen_ = UINT64_MAX;  // the sum of the versions it was built from
};

// The colour of segment number `index` (a stable, well-separated palette).
render::Rgba segmentColour(std::uint32_t index, std::uint8_t alpha);

}  // namespace plumb::viewer
