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

BorderRaster borderRaster(const Plane& plane, std::span<const Eigen::Vector3d> points, double step) {
  BorderRaster result;
  if (points.empty() || !plane.valid || !(step > 0.0)) return result;
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
  result.cell_of.resize(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    const auto x = static_cast<std::size_t>(std::floor((uv[i].x() - low.x()) / step) + kMargin);
    const auto y = static_cast<std::size_t>(std::floor((uv[i].y() - low.y()) / step) + kMargin);
    result.cell_of[i] = y * raster.width + x;
    raster.cells[result.cell_of[i]] = 1;
  }
  const Raster closed = raster.filtered(true).filtered(false);
  // The chessboard distance of each held cell to the nearest empty one, in two passes: each cell
  // takes one more than the least of its neighbours already passed. The margins are empty.
  const std::size_t w = closed.width;
  result.width = w;
  std::vector<std::uint32_t>& cells = result.from_border;
  cells.assign(closed.cells.size(), 0);
  for (std::size_t y = 1; y + 1 < closed.height; ++y) {
    for (std::size_t x = 1; x + 1 < w; ++x) {
      const std::size_t c = y * w + x;
      if (!closed.cells[c]) continue;
      cells[c] = 1 + std::min({cells[c - 1], cells[c - w - 1], cells[c - w], cells[c - w + 1]});
    }
  }
  for (std::size_t y = closed.height - 2; y >= 1; --y) {
    for (std::size_t x = w - 2; x >= 1; --x) {
      const std::size_t c = y * w + x;
      if (!closed.cells[c]) continue;
      cells[c] = std::min(cells[c], 1 + std::min({cells[c + 1], cells[c + w + 1], cells[c + w], cells[c + w - 1]}));
    }
  }
  return result;
}

std::vector<bool> oneSidedBorderPoints(const BorderRaster& raster, const Plane& plane,
                                       std::span<const Eigen::Vector3d> points, std::uint32_t band_cells,
                                       double sigma, double z, double min_offset) {
  std::vector<bool> one_sided(points.size(), false);
  if (raster.cell_of.empty() || !(sigma > 0.0)) return one_sided;
  const std::size_t w = raster.width;
  std::vector<double> sum(raster.from_border.size(), 0.0);
  std::vector<std::uint32_t> count(raster.from_border.size(), 0);
  for (std::size_t i = 0; i < points.size(); ++i) {
    sum[raster.cell_of[i]] += plane.signedDistance(points[i]);
    ++count[raster.cell_of[i]];
  }
  std::vector<std::int8_t> verdict(raster.from_border.size(), -1);  // -1 not yet judged, 0 no, 1 yes
  for (std::size_t i = 0; i < points.size(); ++i) {
    const std::size_t c = raster.cell_of[i];
    if (raster.from_border[c] > band_cells) continue;
    if (verdict[c] < 0) {
      // The cell and its eight neighbours (the margins keep them inside the raster).
      double s = 0.0;
      std::uint32_t n = 0;
      for (std::size_t k : {c - w - 1, c - w, c - w + 1, c - 1, c, c + 1, c + w - 1, c + w, c + w + 1}) {
        s += sum[k];
        n += count[k];
      }
      const double mean = s / static_cast<double>(n);
      verdict[c] = std::abs(mean) > std::max(z * sigma / std::sqrt(static_cast<double>(n)), min_offset) ? 1 : 0;
    }
    one_sided[i] = verdict[c] == 1;
  }
  return one_sided;
}

std::vector<bool> interiorPoints(const Plane& plane, std::span<const Eigen::Vector3d> points, double step) {
  const BorderRaster raster = borderRaster(plane, points, step);
  std::vector<bool> interior(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) interior[i] = raster.interior(i);
  return interior;
}

}  // namespace plumb::reco
