#include "reco/outline.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <memory>
#include <utility>

namespace plumb::reco {
namespace {

constexpr std::uint32_t kNone = ~0u;
constexpr std::uint32_t kPadCells = 2;  // beyond alpha, so the raster's rim stays outside the dilation
constexpr std::size_t kMinCells = 64;   // a single point needs 7 x 7 cells at the coarsest

struct Raster {
  double cell = 0.0;
  double radius_cells = 0.0;  // alpha in cells
  double origin_x = 0.0;      // the lower-left corner of cell (0, 0)
  double origin_y = 0.0;
  double pad_cells = 0.0;  // the lower-left point lies in cell (pad_cells, pad_cells)
  std::uint32_t width = 0;
  std::uint32_t height = 0;
};

// The raster around [lo, hi] padded by alpha and kPadCells, with the cell grown until it has at
// most max_cells cells.
Raster fitRaster(const Eigen::Vector2d& lo, const Eigen::Vector2d& hi, const OutlineOptions& options) {
  const Eigen::Vector2d extent = hi - lo;
  const double max_cells = static_cast<double>(options.max_cells);
  double cell = options.cell_m;
  for (;;) {
    const double pad = std::ceil(options.alpha_m / cell) + kPadCells;
    const double width = std::floor(extent.x() / cell) + 1.0 + 2.0 * pad;
    const double height = std::floor(extent.y() / cell) + 1.0 + 2.0 * pad;
    if (width * height <= max_cells) {
      Raster raster;
      raster.cell = cell;
      // A hair more, so that an alpha of a whole number of cells reaches the cells at just that
      // distance, however alpha / cell rounds.
      raster.radius_cells = options.alpha_m / cell * (1.0 + 1e-9);
      raster.origin_x = lo.x() - pad * cell;
      raster.origin_y = lo.y() - pad * cell;
      raster.pad_cells = pad;
      raster.width = static_cast<std::uint32_t>(width);
      raster.height = static_cast<std::uint32_t>(height);
      return raster;
    }
    // The padding shrinks in cells as the cell grows, so the square-root step may overshoot a
    // little; the floor on the factor makes sure the loop ends.
    cell *= std::max(1.001, std::sqrt(width * height / max_cells));
  }
}

// near[c] = 1 where cell c lies within `radius` cells (centre to centre, Euclidean) of a cell
// whose grid value is `site`, else 0: the exact Euclidean distance transform, thresholded.
// Separable as in Felzenszwalb & Huttenlocher: first the distance to the nearest site in each
// column, g (two sweeps, row by row so they run along memory); then along each row, the squared
// distance is min over x' of (x - x')^2 + g(x')^2. Only whether it reaches radius^2 matters, so
// instead of their lower envelope of parabolas, each x' covers the cells within
// reach(g) = floor(sqrt(radius^2 - g^2)) of it, and one sweep each way finds the covered cells.
// Same answer, no divisions, O(cells) for any radius. g is capped just above the radius: a
// capped cell reaches nothing either way.
void markWithin(const std::vector<std::uint8_t>& grid, std::uint8_t site, const Raster& raster, double radius,
                std::vector<std::int32_t>& column, std::vector<std::uint8_t>& near) {
  const std::size_t width = raster.width;
  const std::size_t height = raster.height;
  const std::int32_t cap = static_cast<std::int32_t>(std::floor(radius)) + 1;
  const double radius2 = radius * radius;
  column.resize(width * height);
  for (std::size_t x = 0; x < width; ++x) column[x] = grid[x] == site ? 0 : cap;
  for (std::size_t y = 1; y < height; ++y) {
    const std::size_t row = y * width;
    for (std::size_t x = 0; x < width; ++x) {
      column[row + x] = grid[row + x] == site ? 0 : std::min(column[row - width + x] + 1, cap);
    }
  }
  for (std::size_t y = height - 1; y-- > 0;) {
    const std::size_t row = y * width;
    for (std::size_t x = 0; x < width; ++x) column[row + x] = std::min(column[row + x], column[row + width + x] + 1);
  }

  std::vector<std::int32_t> reach(static_cast<std::size_t>(cap) + 1);
  for (std::int32_t g = 0; g < cap; ++g) {
    const double g2 = static_cast<double>(g) * g;
    auto h = static_cast<std::int32_t>(std::sqrt(std::max(radius2 - g2, 0.0)));
    while (static_cast<double>(h + 1) * (h + 1) + g2 <= radius2) ++h;  // sqrt may round either way
    while (h > 0 && static_cast<double>(h) * h + g2 > radius2) --h;
    reach[static_cast<std::size_t>(g)] = h;
  }
  const auto far = -static_cast<std::int32_t>(width) - 1;  // beyond any cell, for capped columns
  reach[static_cast<std::size_t>(cap)] = far;

  near.resize(width * height);
  for (std::size_t y = 0; y < height; ++y) {
    const std::int32_t* g = column.data() + y * width;
    std::uint8_t* out = near.data() + y * width;
    std::int32_t right = far;  // the farthest cell covered by a site at or left of x
    for (std::int32_t x = 0; x < static_cast<std::int32_t>(width); ++x) {
      right = std::max(right, x + reach[static_cast<std::size_t>(g[x])]);
      out[x] = static_cast<std::uint8_t>(right >= x);
    }
    std::int32_t left = static_cast<std::int32_t>(width) - far;  // ... at or right of x
    for (std::int32_t x = static_cast<std::int32_t>(width); x-- > 0;) {
      left = std::min(left, x - reach[static_cast<std::size_t>(g[x])]);
      out[x] = static_cast<std::uint8_t>(out[x] | (left <= x));
    }
  }
}

// One marching square: its corners c0 (i, j), c1 (i+1, j), c2 (i+1, j+1), c3 (i, j+1) and the
// midpoints between them walked counter-clockwise as slots 0..7 (c0, e0, c1, e1, c2, e2, c3, e3).
// The inside polygon of a case keeps the inside corners and the crossing midpoints in that order.
// It is convex in every case, the saddles included: there the walk joins the two inside corners
// into one hexagon, i.e. diagonal neighbours are connected, so rings never cross.
struct SquareCase {
  std::array<std::uint8_t, 8> slots{};
  std::uint8_t count = 0;
  std::int32_t area2 = 0;  // twice the polygon's area in doubled lattice units (a full square: 8)
};
constexpr std::array<std::uint8_t, 8> kSlotDx = {0, 1, 2, 2, 2, 1, 0, 0};  // doubled lattice units
constexpr std::array<std::uint8_t, 8> kSlotDy = {0, 0, 0, 1, 2, 2, 2, 1};
constexpr std::array<SquareCase, 16> kCases = [] {
  std::array<SquareCase, 16> cases{};
  for (unsigned code = 0; code < 16; ++code) {
    for (unsigned slot = 0; slot < 8; ++slot) {
      const bool a = (code >> (slot / 2)) & 1u;
      const bool b = (code >> ((slot / 2 + 1) % 4)) & 1u;
      if (slot % 2 == 0 ? a : a != b) cases[code].slots[cases[code].count++] = static_cast<std::uint8_t>(slot);
    }
    SquareCase& square = cases[code];
    for (unsigned s = 0; s < square.count; ++s) {
      const unsigned from = square.slots[s];
      const unsigned to = square.slots[(s + 1) % square.count];
      square.area2 += kSlotDx[from] * kSlotDy[to] - kSlotDy[from] * kSlotDx[to];
    }
  }
  return cases;
}();

// Doubled lattice coordinates of the midpoint of a lattice edge: cell centre (i, j) is (2i, 2j).
// Edge ids: 2 (j width + i) for the edge from (i, j) to the right, + 1 for the one upwards.
std::array<std::int64_t, 2> midpoint(std::uint32_t id, std::uint32_t width) {
  const std::int64_t i = (id >> 1) % width;
  const std::int64_t j = (id >> 1) / width;
  return (id & 1u) ? std::array<std::int64_t, 2>{2 * i, 2 * j + 1} : std::array<std::int64_t, 2>{2 * i + 1, 2 * j};
}

}  // namespace

bool insideRing(std::span<const Eigen::Vector2d> ring, const Eigen::Vector2d& p) {
  bool inside = false;
  for (std::size_t i = 0, j = ring.size() - 1; i < ring.size(); j = i++) {
    const Eigen::Vector2d& a = ring[i];
    const Eigen::Vector2d& b = ring[j];
    if ((a.y() > p.y()) != (b.y() > p.y()) && p.x() < (b.x() - a.x()) * (p.y() - a.y()) / (b.y() - a.y()) + a.x()) {
      inside = !inside;
    }
  }
  return inside;
}

bool Outline::contains(const Eigen::Vector2d& p) const {
  bool inside = false;
  for (const auto& ring : rings) inside ^= insideRing(ring, p);
  return inside;
}

Outline outlineOf(std::span<const Eigen::Vector2d> points, const OutlineOptions& options) {
  assert(options.alpha_m > 0.0 && options.cell_m > 0.0 && "outlineOf needs a positive alpha and cell size");
  assert(options.max_cells >= kMinCells && "max_cells below 64 cannot hold even a single point's raster");
  assert(options.max_cells < (std::size_t{1} << 31) && "max_cells at or above 2^31 overflows the edge ids");
  Outline outline;
  if (points.empty()) return outline;

  // 1. Rasterise.
  Eigen::Vector2d lo = points[0];
  Eigen::Vector2d hi = points[0];
  for (const Eigen::Vector2d& p : points) {
    assert(p.allFinite() && "outlineOf takes finite points: drop NaNs before projecting");
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const Raster raster = fitRaster(lo, hi, options);
  const std::uint32_t width = raster.width;
  const std::uint32_t height = raster.height;
  const std::size_t cells = std::size_t{width} * height;
  std::vector<std::uint8_t> closed(cells, 0);
  const double inv_cell = 1.0 / raster.cell;
  const auto pad = static_cast<std::int32_t>(raster.pad_cells);
  const auto max_x = static_cast<std::int32_t>(width) - 1;
  const auto max_y = static_cast<std::int32_t>(height) - 1;
  constexpr std::size_t kBlock = 256;
  std::array<std::int32_t, kBlock> cell_of;
  for (std::size_t first = 0; first < points.size(); first += kBlock) {
    // Cell indices for a block first, then the stores: apart from the byte stores, the
    // conversions vectorise, three times faster on a million points. Measured from lo, so that a
    // point on a cell line lands where the arithmetic says, and never negative, so truncation is
    // the floor. Clamped only against rounding at the far rim.
    const std::size_t count = std::min(kBlock, points.size() - first);
    for (std::size_t k = 0; k < count; ++k) {
      const Eigen::Vector2d& p = points[first + k];
      const std::int32_t x = std::min(pad + static_cast<std::int32_t>((p.x() - lo.x()) * inv_cell), max_x);
      const std::int32_t y = std::min(pad + static_cast<std::int32_t>((p.y() - lo.y()) * inv_cell), max_y);
      cell_of[k] = y * static_cast<std::int32_t>(width) + x;
    }
    for (std::size_t k = 0; k < count; ++k) closed[static_cast<std::size_t>(cell_of[k])] = 1;
  }

  // 2. Close: the dilation is every cell within alpha of a point; the closing drops the cells
  // within alpha of a cell outside the dilation. The same disk both times keeps every occupied
  // cell (a lone cell stays itself) and leaves exactly the union of disks of radius alpha that
  // miss all points carved away.
  std::vector<std::int32_t> column;
  std::vector<std::uint8_t> dilated;
  markWithin(closed, 1, raster, raster.radius_cells, column, dilated);
  markWithin(dilated, 0, raster, raster.radius_cells, column, closed);
  for (std::uint8_t& c : closed) c = static_cast<std::uint8_t>(c == 0);

  // 3 and 4. One sweep over the marching squares (the rings are linked after it): each emits the boundary segments of
  // its inside polygon (inside on the left, so outer rings run counter-clockwise and holes clockwise) and that
  // polygon's triangles. Vertices are shared through three row buffers indexed by doubled x: the square row's bottom
  // line, its mid line (vertical-edge midpoints) and its top line.
  const auto next = std::make_unique_for_overwrite<std::uint32_t[]>(2 * cells);
  std::vector<std::uint32_t> segment_starts;
  std::vector<std::uint32_t> bottom(2 * std::size_t{width}, kNone), middle(width, kNone), top(bottom);
  const double half_cell = 0.5 * raster.cell;
  std::int64_t area2 = 0;  // twice the area in doubled lattice units, exact
  for (std::uint32_t j = 0; j + 1 < height; ++j) {
    const std::uint8_t* row0 = closed.data() + std::size_t{j} * width;
    const std::uint8_t* row1 = row0 + width;
    auto vertexAt = [&](std::uint32_t dx2, std::uint32_t dy2) {
      std::uint32_t& slot = dy2 == 0 ? bottom[dx2] : dy2 == 1 ? middle[dx2 / 2] : top[dx2];
      if (slot == kNone) {
        slot = static_cast<std::uint32_t>(outline.vertices.size());
        outline.vertices.emplace_back(raster.origin_x + (1.0 + dx2) * half_cell,
                                      raster.origin_y + (1.0 + 2.0 * j + dy2) * half_cell);
      }
      return slot;
    };
    for (std::uint32_t i = 0; i + 1 < width; ++i) {
      const auto code = static_cast<unsigned>(row0[i] | (row0[i + 1] << 1) | (row1[i + 1] << 2) | (row1[i] << 3));
      if (code == 0) continue;
      if (code == 15) {
        // A run of full squares is one quad: far fewer triangles on large segments.
        std::uint32_t end = i + 1;
        while (end + 1 < width && row0[end + 1] && row1[end + 1]) ++end;
        const std::uint32_t c0 = vertexAt(2 * i, 0), c1 = vertexAt(2 * end, 0);
        const std::uint32_t c2 = vertexAt(2 * end, 2), c3 = vertexAt(2 * i, 2);
        outline.triangles.push_back({c0, c1, c2});
        outline.triangles.push_back({c0, c2, c3});
        area2 += 8 * std::int64_t{end - i};
        i = end - 1;
        continue;
      }
      const SquareCase& square = kCases[code];
      std::array<std::uint32_t, 8> ids{};
      for (std::uint8_t s = 0; s < square.count; ++s) {
        ids[s] = vertexAt(2 * i + kSlotDx[square.slots[s]], kSlotDy[square.slots[s]]);
      }
      for (std::uint8_t s = 1; s + 1 < square.count; ++s) outline.triangles.push_back({ids[0], ids[s], ids[s + 1u]});
      area2 += square.area2;
      const std::uint32_t base = 2 * (j * width + i);
      const std::array<std::uint32_t, 4> edge_ids = {base, base + 3, base + 2 * width, base + 1};  // e0..e3
      for (std::uint8_t s = 0; s < square.count; ++s) {
        const std::uint8_t from = square.slots[s];
        const std::uint8_t to = square.slots[static_cast<std::size_t>((s + 1) % square.count)];
        if (from % 2 == 1 && to % 2 == 1) {
          next[edge_ids[from / 2]] = edge_ids[to / 2];
          segment_starts.push_back(edge_ids[from / 2]);
        }
      }
    }
    std::swap(bottom, top);
    std::fill(top.begin(), top.end(), kNone);
    std::fill(middle.begin(), middle.end(), kNone);
  }
  outline.area_m2 = static_cast<double>(area2) * half_cell * half_cell * 0.5;

  // Link the segments into rings. Every boundary midpoint starts exactly one segment, so following
  // next[] from any start returns to it; following marks the way with kNone.
  std::vector<std::array<std::int64_t, 2>> ring;
  for (const std::uint32_t start : segment_starts) {
    if (next[start] == kNone) continue;
    ring.clear();
    std::uint32_t id = start;
    do {
      ring.push_back(midpoint(id, width));
      id = std::exchange(next[id], kNone);
    } while (id != start);
    // Marching squares never doubles back, so a vertex is redundant exactly when the direction
    // does not turn there; the test is exact in lattice units.
    std::vector<Eigen::Vector2d>& kept = outline.rings.emplace_back();
    const std::size_t n = ring.size();
    for (std::size_t k = 0; k < n; ++k) {
      const auto& a = ring[(k + n - 1) % n];
      const auto& b = ring[k];
      const auto& c = ring[(k + 1) % n];
      if ((b[0] - a[0]) * (c[1] - b[1]) == (b[1] - a[1]) * (c[0] - b[0])) continue;
      kept.emplace_back(raster.origin_x + (1.0 + static_cast<double>(b[0])) * half_cell,
                        raster.origin_y + (1.0 + static_cast<double>(b[1])) * half_cell);
    }
  }
  outline.cell_m = raster.cell;
  outline.raster_width_cells = width;
  outline.raster_height_cells = height;
  return outline;
}

PlaneOutline outlineOnPlane(const Plane& plane, std::span<const Eigen::Vector3d> points,
                            const OutlineOptions& options) {
  assert(plane.valid && "an outline needs a plane");
  PlaneOutline result;
  result.origin = plane.centroid;
  result.axis_u = plane.tangent;
  result.axis_v = plane.bitangent;
  std::vector<Eigen::Vector2d> projected;
  projected.reserve(points.size());
  for (const Eigen::Vector3d& p : points) {
    const Eigen::Vector3d d = p - plane.centroid;
    projected.emplace_back(d.dot(plane.tangent), d.dot(plane.bitangent));
  }
  result.shape = outlineOf(projected, options);
  return result;
}

}  // namespace plumb::reco
