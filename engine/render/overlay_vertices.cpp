#include "engine/render/overlay_vertices.h"

namespace plumb::render {
namespace {

shader::OverlayVertex vertex(const Eigen::Vector3d& position, const Eigen::Vector3d& eye, std::uint32_t colour,
                             std::uint32_t flags) {
  shader::OverlayVertex v{};
  const Eigen::Vector3f relative = (position - eye).cast<float>();
  v.position[0] = relative.x();
  v.position[1] = relative.y();
  v.position[2] = relative.z();
  v.colour = colour;
  v.flags = flags;
  return v;
}

// The two triangles of a quad from four corner offsets (-1 or +1 each).
constexpr float kQuad[6][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, -1}, {1, 1}, {-1, 1}};

}  // namespace

std::vector<shader::OverlayVertex> overlayVertices(const OverlayScene& scene, const Eigen::Vector3d& eye) {
  std::vector<shader::OverlayVertex> vertices;
  for (const OverlayScene::Polygon& polygon : scene.polygons) {
    const std::uint32_t colour = packRgba(polygon.colour);
    for (std::size_t i = 0; i + 2 < polygon.triangles.size(); i += 3) {
      for (std::size_t k = 0; k < 3; ++k) vertices.push_back(vertex(polygon.triangles[i + k], eye, colour, 0));
    }
  }
  for (const OverlayScene::Line& line : scene.lines) {
    const std::uint32_t flags = shader::kOverlayLine | (line.on_top ? shader::kOverlayOnTop : 0u);
    const Eigen::Vector3f a = (line.a - eye).cast<float>(), b = (line.b - eye).cast<float>();
    for (const auto& corner : kQuad) {
      // corner[0]: which end (-1: a, +1: b); corner[1]: which side. Seen from b, a's left is
      // b's right: the side flips with the end so that the quad does not twist.
      const bool at_b = corner[0] > 0;
      shader::OverlayVertex v = vertex(at_b ? line.b : line.a, eye, packRgba(line.colour), flags);
      const Eigen::Vector3f& other = at_b ? a : b;
      v.other[0] = other.x();
      v.other[1] = other.y();
      v.other[2] = other.z();
      v.offset_px[0] = 0.5f * line.width_px * corner[1] * (at_b ? -1.0f : 1.0f);
      vertices.push_back(v);
    }
  }
  for (const OverlayScene::Marker& marker : scene.markers) {
    const std::uint32_t flags = shader::kOverlayMarker | (marker.on_top ? shader::kOverlayOnTop : 0u);
    for (const auto& corner : kQuad) {
      shader::OverlayVertex v = vertex(marker.position, eye, packRgba(marker.colour), flags);
      v.offset_px[0] = 0.5f * marker.size_px * corner[0];
      v.offset_px[1] = 0.5f * marker.size_px * corner[1];
      vertices.push_back(v);
    }
  }
  return vertices;
}

}  // namespace plumb::render
