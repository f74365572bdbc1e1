// The interior of a planar point set by a closed raster (interior_points.h).

#include "reco/interior_points.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace plumb::reco {
namespace {

// A raster of cells on the plane, one byte each, with a margin of two empty cells on every side
// so that the 3 x 3 operations below never leave it.
struct Raster {
  std::size_t width = 0, height = 0;
  std::vector<std::uint8_t> cells;

  std::uint8_t at(std::size_t x, std::size_t y) const { return cells[y * width + x]; }

  // Each cell becomes the maximum (dilate) or the minimum (erode) of the 3 x 3 cells around it.
  Raster filtered(bool dilate) const {
    Raster result{width, height, std::vector<std::uint8_t>(cells.size(), 0)};
    for (std::size_t y = 1; y + 1 < height; ++y) {
      for (std::size_t x = 1; x + 1 < width; ++x) {
        std::uint8_t value = dilate ? 0 : 1;
        for (std::size_t dy = 0; dy < 3; ++dy) {
          for (std::size_t dx = 0; dx < 3; ++dx) {
            const std::uint8_t c = at(x + dx - 1, y + dy - 1);
            value = dilate ? std::max(value, c) : std::min(value, c);
          }
        }
        result.cells[y * width + x] = value;
      }
    }
    return result;
  }
};

}  // namespace

std::vector<bool> interiorPoints(const Plane& plane, std::span<const Eigen::Vector3d> points, double step) {
  std::vector<bool> interior(points.size(), false);
  if (points.empty() || !plane.valid || !(step > 0.0)) return interior;
  std::vector<Eigen::Vector2d> uv(points.size());
  Eigen::Vector2d low = Eigen::Vector2d::Constant(INFINITY);
  Eigen::Vector2d high = Eigen::Vector2d::Constant(-INFINITY);
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Eigen::Vector3d q = points[i] - plane.centroid;
    uv[i] = {plane.tangent.dot(q), plane.bitangent.dot(q)};
    low = low.cwiseMin(uv[i]);
    high = high.cwiseMax(uv[i]);
  }
  constexpr double kMargin = 2.0;
  // Cells along one axis of the raster for an extent of the points, margins included.
  const auto cellsAcross = [&](double extent) { return std::floor(extent / step) + 1.0 + 2.0 * kMargin; };
  while (cellsAcross(high.x() - low.x()) * cellsAcross(high.y() - low.y()) > static_cast<double>(kMaxInteriorCells)) {
    step *= 2.0;
  }

  Raster raster;
  raster.width = static_cast<std::size_t>(cellsAcross(high.x() - low.x()));
  raster.height = static_cast<std::size_t>(cellsAcross(high.y() - low.y()));
  raster.cells.assign(raster.width * raster.height, 0);
  std::vector<std::size_t> cell_of(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    const auto x = static_cast<std::size_t>(std::floor((uv[i].x() - low.x()) / step) + kMargin);
    const auto y = static_cast<std::size_t>(std::floor((uv[i].y() - low.y()) / step) + kMargin);
    cell_of[i] = y * raster.width + x;
    raster.cells[cell_of[i]] = 1;
  }
  const Raster inner = raster.filtered(true).filtered(false).filtered(false);
  for (std::size_t i = 0; i < points.size(); ++i) interior[i] = inner.cells[cell_of[i]] != 0;
  return interior;
}

}  // namespace plumb::reco
