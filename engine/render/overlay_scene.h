#pragma once
// What the overlay pass draws over the cloud, in world coordinates (double precision):
// translucent polygons (a segment's regression polygon, as triangles), lines (edges, the growing
// outline) and markers (corners, snap candidates). Depth-tested against the cloud unless on_top.
//
// A plain value: the viewer builds a new one when its ECS changes and hands it to the renderer.

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <vector>

namespace plumb::render {

using Rgba = std::array<std::uint8_t, 4>;  // straight alpha

// As the shaders read a colour: R in the lowest byte.
inline std::uint32_t packRgba(const Rgba& c) {
  return std::uint32_t{c[0]} | std::uint32_t{c[1]} << 8 | std::uint32_t{c[2]} << 16 | std::uint32_t{c[3]} << 24;
}

struct OverlayScene {
  struct Polygon {
    std::vector<Eigen::Vector3d> triangles;  // three corners per triangle
    Rgba colour{255, 200, 0, 96};
  };
  struct Line {
    Eigen::Vector3d a, b;
    Rgba colour{255, 255, 255, 255};
    float width_px = 2.0f;
    bool on_top = false;
  };
  struct Marker {
    Eigen::Vector3d position;
    Rgba colour{255, 64, 64, 255};
    float size_px = 9.0f;  // the side of its square
    bool on_top = true;
  };
  std::vector<Polygon> polygons;
  std::vector<Line> lines;
  std::vector<Marker> markers;

  bool empty() const { return polygons.empty() && lines.empty() && markers.empty(); }
};

}  // namespace plumb::render
