#include "ui/viewer/scene_overlay.h"

#include <Eigen/Geometry>
#include <array>

#include "cad/measurement.h"
#include "cad/polygon_mesh.h"
#include "engine/ecs/registry.h"
#include "ui/viewer/components.h"

namespace plumb::viewer {
namespace {

constexpr render::Rgba kPolygonRim{255, 255, 255, 255};
constexpr render::Rgba kDrawing{80, 255, 120, 255};      // what a tool is drawing, a measurement's terms
constexpr render::Rgba kMeasurement{255, 200, 40, 255};  // measurements' dimension lines
constexpr render::Rgba kArrow{255, 120, 255, 255};       // the direction

// A polygon, or a prism when `extrusion` is non-zero: its faces filled, its sides drawn.
void addPolygon(render::OverlayScene& overlay, const std::vector<Eigen::Vector3d>& ring,
                const Eigen::Vector3d& extrusion, render::Rgba fill, render::Rgba rim, float width_px) {
  if (ring.size() < 3 || cad::findPolygonProblem(ring)) return;
  cad::Polygon polygon;
  polygon.vertices = ring;
  polygon.extrusion = extrusion;
  const cad::TriangleMesh mesh = cad::prismMesh(polygon);
  render::OverlayScene::Polygon faces;
  faces.colour = fill;
  for (const auto& triangle : mesh.triangles) {
    for (const std::uint32_t vertex : triangle) faces.triangles.push_back(mesh.positions[vertex]);
  }
  overlay.polygons.push_back(std::move(faces));
  const bool prism = !extrusion.isZero(0.0);
  for (std::size_t i = 0; i < ring.size(); ++i) {
    const Eigen::Vector3d& a = ring[i];
    const Eigen::Vector3d& b = ring[(i + 1) % ring.size()];
    overlay.lines.push_back({a, b, rim, width_px, false});
    if (prism) {
      overlay.lines.push_back({a + extrusion, b + extrusion, rim, width_px, false});
      overlay.lines.push_back({a, a + extrusion, rim, width_px, false});
    }
  }
}

// An arrow from `from` along `direction`, `length` long, its head two short strokes.
void addArrow(render::OverlayScene& overlay, const Eigen::Vector3d& from, const Eigen::Vector3d& direction,
              double length) {
  const Eigen::Vector3d tip = from + length * direction;
  Eigen::Vector3d side = direction.unitOrthogonal();
  overlay.lines.push_back({from, tip, kArrow, 3.0f, true});
  for (const double sign : {-1.0, 1.0}) {
    overlay.lines.push_back({tip, tip - 0.25 * length * direction + sign * 0.12 * length * side, kArrow, 3.0f, true});
  }
  overlay.markers.push_back({tip, kArrow, 7.0f, true});
}

// What the drawing tools show between clicks.
void addDrawing(render::OverlayScene& overlay, const ecs::Registry& registry, const ToolState& tool) {
  const DrawingState& d = tool.drawing;
  if (tool.active == Tool::kPolygon) {
    for (std::size_t i = 0; i < d.vertices.size(); ++i) {
      overlay.markers.push_back({d.vertices[i], kDrawing, 8.0f, true});
      if (i + 1 < d.vertices.size()) overlay.lines.push_back({d.vertices[i], d.vertices[i + 1], kDrawing, 2.5f, true});
    }
    if (d.preview && !d.vertices.empty()) {
      if (d.rectangle && d.vertices.size() == 2) {
        const Eigen::Vector3d side = (d.vertices[1] - d.vertices[0]).normalized();
        const Eigen::Vector3d width = (*d.preview - d.vertices[1]) - (*d.preview - d.vertices[1]).dot(side) * side;
        const std::array<Eigen::Vector3d, 4> corners{d.vertices[0], d.vertices[1], d.vertices[1] + width,
                                                     d.vertices[0] + width};
        for (std::size_t i = 0; i < 4; ++i)
          overlay.lines.push_back({corners[i], corners[(i + 1) % 4], kDrawing, 2.0f, true});
      } else {
        overlay.lines.push_back({d.vertices.back(), *d.preview, kDrawing, 1.5f, true});
      }
    }
  }
  const Polygon* polygon = registry.tryGet<Polygon>(d.polygon);
  if (polygon && d.preview) {
    // The polygon where the click would put it: moved, copied or extruded.
    if (tool.active == Tool::kMove && d.base) {
      std::vector<Eigen::Vector3d> moved = polygon->vertices;
      for (Eigen::Vector3d& vertex : moved) vertex += *d.preview - *d.base;
      addPolygon(overlay, moved, polygon->extrusion, {80, 255, 120, 60}, kDrawing, 2.0f);
      overlay.lines.push_back({*d.base, *d.preview, kDrawing, 1.5f, true});
    }
    if (tool.active == Tool::kExtrude && d.preview_extrusion) {
      addPolygon(overlay, polygon->vertices, *d.preview_extrusion, {80, 255, 120, 60}, kDrawing, 2.0f);
    }
  }
  if (d.preview) overlay.markers.push_back({*d.preview, kDrawing, 6.0f, true});
  if (d.direction && tool.active != Tool::kNavigate && tool.active != Tool::kGrow && tool.active != Tool::kMeasure) {
    // From the move's base, else from the feature it was found on; locked, it reaches the preview.
    Eigen::Vector3d from = d.direction->anchor;
    if (d.base) from = *d.base;
    const double length = d.preview ? std::max(0.2, (*d.preview - from).norm()) : 0.5;
    addArrow(overlay, from, d.direction->vector, d.direction_locked ? length : 0.3);
  }
  if (d.base) overlay.markers.push_back({*d.base, kDrawing, 10.0f, true});
}

}  // namespace

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
                                 registry.version<ToolState>() + registry.version<Selection>() +
                                 registry.version<Polygon>() + registry.version<Measurement>();
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
  registry.view<Polygon>().each([&](ecs::Entity entity, const Polygon& polygon) {
    const bool selected = registry.has<Selection>(entity);
    addPolygon(*overlay, polygon.vertices, polygon.extrusion,
               selected ? render::Rgba{255, 255, 255, 110} : render::Rgba{200, 200, 255, 70}, kPolygonRim,
               selected ? 3.0f : 2.0f);
  });
  // Each measurement's dimension line, its ends marked (its value is labelled by the palette).
  registry.view<Measurement>().each([&](ecs::Entity entity, const Measurement& measurement) {
    const cad::MeasureValue value = cad::measure(measurement.kind, measurement.terms);
    const bool selected = registry.has<Selection>(entity);
    const render::Rgba colour = selected ? render::Rgba{255, 255, 255, 255} : kMeasurement;
    overlay->markers.push_back({value.from, colour, 8.0f, true});
    if (value.to != value.from) {
      overlay->markers.push_back({value.to, colour, 8.0f, true});
      overlay->lines.push_back({value.from, value.to, colour, selected ? 3.5f : 2.5f, true});
    }
  });
  registry.view<ToolState>().each([&](ecs::Entity, const ToolState& tool) {
    addDrawing(*overlay, registry, tool);
    if (tool.active == Tool::kMeasure) {
      for (const cad::MeasureTerm& term : tool.measure_terms)
        overlay->markers.push_back({term.point, kDrawing, 9.0f, true});
    }
    if (tool.hover) {
      // What the cursor snaps to: yellow for a corner, white for an edge, cyan for a plane.
      const render::Rgba colour = (tool.hover->kind == Snap::Kind::kCorner || tool.hover->kind == Snap::Kind::kVertex)
                                      ? render::Rgba{255, 230, 0, 255}
                                  : tool.hover->kind == Snap::Kind::kEdge ? render::Rgba{255, 255, 255, 255}
                                                                          : render::Rgba{0, 230, 255, 255};
      overlay->markers.push_back(
          {tool.hover->position, colour,
           tool.hover->kind == Snap::Kind::kCorner || tool.hover->kind == Snap::Kind::kVertex ? 15.0f : 11.0f, true});
    }
  });
  overlay_ = std::move(overlay);
  return overlay_;
}

}  // namespace plumb::viewer
