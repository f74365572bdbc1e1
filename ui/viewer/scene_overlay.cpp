#include "ui/viewer/scene_overlay.h"

#include <array>

#include "engine/ecs/registry.h"
#include "ui/viewer/components.h"

namespace plumb::viewer {

render::Rgba segmentColour(std::uint32_t index, std::uint8_t alpha) {
  // Colour-blind-friendly hues (Okabe and Ito), cycled.
  static constexpr std::array<render::Rgba, 7> kPalette{{{230, 159, 0, 255},
                                                         {86, 180, 233, 255},
                                                         {0, 158, 115, 255},
                                                         {240, 228, 66, 255},
                                                         {0, 114, 178, 255},
                                                         {213, 94, 0, 255},
                                                         {204, 121, 167, 255}}};
  render::Rgba colour = kPalette[index % kPalette.size()];
  colour[3] = alpha;
  return colour;
}

std::shared_ptr<const render::OverlayScene> SceneOverlay::update(const ecs::Registry& registry) {
  const std::uint64_t versions = registry.version<Segment>() + registry.version<Edge>() + registry.version<Corner>() +
                                 registry.version<ToolState>() + registry.version<Selection>();
  if (overlay_ && versions == seen_) return overlay_;
  seen_ = versions;
  auto overlay = std::make_shared<render::OverlayScene>();
  registry.view<Segment>().each([&](ecs::Entity entity, const Segment& segment) {
    if (!segment.outline) return;
    const bool selected = registry.has<Selection>(entity);
    const reco::PlaneOutline& outline = *segment.outline;
    render::OverlayScene::Polygon polygon;
    polygon.colour = segmentColour(entity.index, segment.growing ? 140 : (selected ? 150 : 90));
    polygon.triangles.reserve(outline.shape.triangles.size() * 3);
    for (const auto& triangle : outline.shape.triangles) {
      for (const std::uint32_t vertex : triangle)
        polygon.triangles.push_back(outline.toWorld(outline.shape.vertices[vertex]));
    }
    overlay->polygons.push_back(std::move(polygon));
    render::Rgba rim = segmentColour(entity.index, 255);
    if (segment.growing) rim = {255, 255, 255, 255};
    for (const auto& ring : outline.shape.rings) {
      for (std::size_t i = 0; i < ring.size(); ++i) {
        overlay->lines.push_back({outline.toWorld(ring[i]), outline.toWorld(ring[(i + 1) % ring.size()]), rim,
                                  selected ? 3.0f : 1.5f, false});
      }
    }
  });
  registry.view<Edge>().each([&](ecs::Entity, const Edge& edge) {
    overlay->lines.push_back({edge.start, edge.end, {255, 255, 255, 255}, 2.5f, false});
  });
  registry.view<Corner>().each([&](ecs::Entity, const Corner& corner) {
    overlay->markers.push_back({corner.position, {255, 64, 64, 255}, 11.0f, true});
  });
  registry.view<ToolState>().each([&](ecs::Entity, const ToolState& tool) {
    if (tool.measure_started || tool.measure_done) {
      overlay->markers.push_back({tool.measure_from, {80, 255, 120, 255}, 9.0f, true});
    }
    if (tool.measure_done) {
      overlay->markers.push_back({tool.measure_to, {80, 255, 120, 255}, 9.0f, true});
      overlay->lines.push_back({tool.measure_from, tool.measure_to, {80, 255, 120, 255}, 2.5f, true});
    }
    if (tool.hover) {
      // What the cursor snaps to: yellow for a corner, white for an edge, cyan for a plane.
      const render::Rgba colour = tool.hover->kind == Snap::Kind::kCorner ? render::Rgba{255, 230, 0, 255}
                                  : tool.hover->kind == Snap::Kind::kEdge ? render::Rgba{255, 255, 255, 255}
                                                                          : render::Rgba{0, 230, 255, 255};
      overlay->markers.push_back(
          {tool.hover->position, colour, tool.hover->kind == Snap::Kind::kCorner ? 15.0f : 11.0f, true});
    }
  });
  overlay_ = std::move(overlay);
  return overlay_;
}

}  // namespace plumb::viewer
