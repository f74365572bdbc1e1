// Per-node grid subsampling and the recursive split into children.
//
//   1. A node with at most leaf_max_points points, or at a level whose cells are smaller than
//      kMinCellSize, is a leaf: it keeps all its points.
//   2. Otherwise, thin its points to about one point per occupied cell of the 128^3 grid over
//      the node, the points of coarser levels included: each grid cell keeps, of its own points,
//      the ones of lowest position hash, as many as its share of what its 3^3 neighbourhood
//      lacks (its occupied cells less the coarser points there), in proportion to its points.
//      Move those points to the front.
//   3. Partition the rest by child octant and build each non-empty child the same way, passing
//      down the coarser points and this node's own selection that lie in the child.
//   4. Hand the node to the sink after its children, with the mask of the children that exist.

#include "engine/lod/node_indexer.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstring>
#include <limits>

#include "engine/lod/octree_format.h"

namespace plumb::lod {
namespace {

constexpr std::uint32_t kEmpty = std::numeric_limits<std::uint32_t>::max();
constexpr std::uint32_t kReach = 1;   // a grid cell's neighbourhood: the cells within this many steps
std::uint64_t mix(std::uint64_t h) {  // the splitmix64 finaliser
  h = (h ^ (h >> 30)) * 0xBF58476D1CE4E5B9ULL;
  h = (h ^ (h >> 27)) * 0x94D049BB133111EBULL;
  return h ^ (h >> 31);
}

double unitInterval(std::uint64_t h) {
  return static_cast<double>(h >> 11) * 0x1.0p-53;
}

// Below a tenth of a millimetre a node stops splitting: its points are as good as duplicates.
constexpr double kMinCellSize = 1e-4 * kSamplingGrid;

}  // namespace

std::uint64_t thinningHash(const Position& p) {
  std::uint64_t h = 0x9E3779B97F4A7C15ULL;
  for (const double c : p) {
    std::uint64_t bits = 0;
    std::memcpy(&bits, &c, sizeof bits);
    h = mix(h ^ (bits + 0x9E3779B97F4A7C15ULL + (h << 6) + (h >> 2)));
  }
  return h;
}

GridPlace placeOf(const Cube& cube, const Position& p) {
  const double inverse = 1.0 / cube.size;  // Cube::cellAt's scale is 2^L times this, exactly
  GridPlace place{};
  for (std::size_t a = 0; a < 3; ++a) {
    const double steps = std::floor((p[a] - cube.origin[a]) * inverse * 0x1p32);
    place[a] = static_cast<std::uint32_t>(std::clamp(steps, 0.0, 0x1p32 - 1.0));
  }
  return place;
}

namespace {

// The thinning's tie-break between points of equal hash_high: a hash of their places.
std::uint64_t placeHash(const GridPlace& place) {
  return mix((std::uint64_t{place[0]} << 32 | place[1]) ^ mix(std::uint64_t{place[2]} + 0x9E3779B97F4A7C15ULL));
}

}  // namespace

NodeIndexer::NodeIndexer(const Cube& cube, std::uint32_t leaf_max_points)
    : cube_(cube), leaf_max_points_(leaf_max_points) {}

bool NodeIndexer::isLeaf(const CellKey& key, std::size_t count) const {
  return count <= leaf_max_points_ || key.level >= kMaxLevel || cube_.cellSize(key.level) < kMinCellSize;
}

namespace {

// Sorts `keys` (a grid cell in the high 32 bits, an index in the low) by cell, stably: a
// least-significant-digit radix sort in two passes of 11 bits over the 21 bits of a 128^3 cell,
// whose reads and writes run in sequence where a table of 2^21 cells would be read at random.
void sortByCell(std::vector<std::uint64_t>& keys, std::vector<std::uint64_t>& scratch) {
  constexpr int kBits = 11;
  constexpr std::size_t kBuckets = std::size_t{1} << kBits;
  static_assert(2 * kBits >= 21, "two passes cover a 128^3 cell index");
  scratch.resize(keys.size());
  for (int shift = 32; shift < 32 + 2 * kBits; shift += kBits) {
    std::array<std::uint32_t, kBuckets + 1> starts{};
    for (const std::uint64_t key : keys) ++starts[((key >> shift) & (kBuckets - 1)) + 1];
    for (std::size_t b = 0; b < kBuckets; ++b) starts[b + 1] += starts[b];
    for (const std::uint64_t key : keys) scratch[starts[(key >> shift) & (kBuckets - 1)]++] = key;
    keys.swap(scratch);
  }
}

}  // namespace

std::size_t NodeIndexer::selectSubsample(const CellKey& key, std::span<BuildPoint> points,
                                         std::span<const GridPlace> coarser) {
  // A grid cell of the node is a cell of 7 levels further down (128 = 2^7): per axis, the low 7
  // bits of that cell's coordinate (the bits above are the node's, for every point inside it).
  const std::uint32_t grid_level = key.level + 7;
  auto locate = [&](const GridPlace& p) {
    std::uint64_t cell = 0;
    for (std::size_t a = 0; a < 3; ++a) cell = cell * kSamplingGrid + (cellOf(p[a], grid_level) & (kSamplingGrid - 1));
    return cell;
  };
  static_assert(kSamplingGrid == 128, "the grid cells are the cells 7 levels below the node's");

  // 1. The occupied grid cells (slots), in cell order, with their coarser points and this node's
  //    own: both sorted by cell, then merged. order_ lists the node's points cell by cell.
  cell_keys_.resize(points.size());
  score_.resize(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    cell_keys_[i] = locate(points[i].place) << 32 | i;
    score_[i] = points[i].hash_high;
  }
  sortByCell(cell_keys_, sort_scratch_);
  coarser_keys_.resize(coarser.size());
  for (std::size_t i = 0; i < coarser.size(); ++i) coarser_keys_[i] = locate(coarser[i]) << 32;
  sortByCell(coarser_keys_, sort_scratch_);
  slots_.clear();
  order_.resize(points.size());
  std::size_t own_at = 0, coarser_at = 0;
  while (own_at < cell_keys_.size() || coarser_at < coarser_keys_.size()) {
    const std::uint64_t own_cell = own_at < cell_keys_.size() ? cell_keys_[own_at] >> 32 : kEmpty;
    const std::uint64_t coarser_cell = coarser_at < coarser_keys_.size() ? coarser_keys_[coarser_at] >> 32 : kEmpty;
    Slot slot{static_cast<std::uint32_t>(std::min(own_cell, coarser_cell))};
    slot.first = static_cast<std::uint32_t>(own_at);
    for (; coarser_at < coarser_keys_.size() && coarser_keys_[coarser_at] >> 32 == slot.cell; ++coarser_at)
      ++slot.coarser;
    for (; own_at < cell_keys_.size() && cell_keys_[own_at] >> 32 == slot.cell; ++own_at) {
      order_[own_at] = static_cast<std::uint32_t>(cell_keys_[own_at]);
      ++slot.own;
    }
    slots_.push_back(slot);
  }

  // 2. Each cell's quota: its share of what its 3^3 neighbourhood still needs to reach about one
  //    point per occupied cell, in proportion to its own points, with a deterministic random
  //    rounding. A cell counts as occupied in proportion to its points, up to the
  //    neighbourhood's mean: the few points of a noise tail that reach into the next layer of
  //    cells occupy it only a little, so a level's density on a wall does not grow with the
  //    number of points scanned (ten times the points fill ten times the tail cells).
  //    The neighbours lie in 9 rows of z (x and y one step either way); since the slots come in
  //    cell order, one cursor per row walks forward through them.
  std::array<std::size_t, (2 * kReach + 1) * (2 * kReach + 1)> cursors{};
  for (Slot& slot : slots_) {
    slot.quota = 0;
    if (slot.own == 0) continue;  // the cursors catch up at the next cell that has points
    const std::uint32_t cx = slot.cell / (kSamplingGrid * kSamplingGrid);
    const std::uint32_t cy = slot.cell / kSamplingGrid % kSamplingGrid;
    const std::uint32_t cz = slot.cell % kSamplingGrid;
    const std::uint32_t z_low = cz - std::min(cz, kReach), z_high = std::min(cz + kReach, kSamplingGrid - 1);
    std::array<std::uint32_t, (2 * kReach + 1) * (2 * kReach + 1) * (2 * kReach + 1)> points_around;
    std::size_t around = 0;  // occupied cells in the neighbourhood: their points in points_around
    std::uint32_t held = 0, own = 0;
    for (std::uint32_t x = cx - std::min(cx, kReach); x <= std::min(cx + kReach, kSamplingGrid - 1); ++x) {
      for (std::uint32_t y = cy - std::min(cy, kReach); y <= std::min(cy + kReach, kSamplingGrid - 1); ++y) {
        // One cursor per offset of the row: rows a cell at the grid's edge lacks are skipped,
        // and each cursor still only moves on.
        std::size_t& at = cursors[(x + kReach - cx) * (2 * kReach + 1) + (y + kReach - cy)];
        const std::uint32_t base = (x * kSamplingGrid + y) * kSamplingGrid;
        while (at < slots_.size() && slots_[at].cell < base + z_low) ++at;
        for (std::size_t other = at; other < slots_.size() && slots_[other].cell <= base + z_high; ++other) {
          points_around[around++] = slots_[other].coarser + slots_[other].own;
          held += slots_[other].coarser;
          own += slots_[other].own;
        }
      }
    }
    // A neighbour of p points occupies min(1, p / mean) of a cell, mean = total / around: whole
    // where p * around >= total, and the others together (their points) * around / total.
    const std::uint64_t total = held + own;
    std::uint64_t whole = 0, partial_points = 0;
    for (std::size_t n = 0; n < around; ++n) {
      const bool full = std::uint64_t{points_around[n]} * around >= total;
      whole += full;
      partial_points += full ? 0 : points_around[n];
    }
    const double occupied =
        static_cast<double>(whole) + static_cast<double>(partial_points * around) / static_cast<double>(total);
    if (occupied <= held) continue;
    const double fraction = std::min(1.0, (occupied - held) / own);
    const double share = fraction * slot.own;
    const double dither = unitInterval(mix(slot.cell ^ (std::uint64_t{key.level} << 32) ^ key.x * 0x9E3779B1ULL ^
                                           key.y * 0x85EBCA77ULL ^ key.z * 0xC2B2AE3DULL));
    slot.quota = static_cast<std::uint32_t>(std::floor(share + dither));
  }

  // 3. In each cell, keep the `quota` points of lowest hash.
  selected_.assign(points.size(), 0);
  for (const Slot& slot : slots_) {
    if (slot.quota == 0) continue;
    const auto begin = order_.begin() + slot.first;
    const auto end = begin + slot.own;
    const auto keep = begin + std::min(slot.quota, slot.own);
    // By the hash's high half, then by a hash of the place; ties of both (duplicates) are broken
    // by input position, so the choice is deterministic. A cell that keeps all needs no ranking.
    if (keep != end) {
      std::nth_element(begin, keep, end, [&](std::uint32_t a, std::uint32_t b) {
        if (score_[a] != score_[b]) return score_[a] < score_[b];
        const std::uint64_t hash_a = placeHash(points[a].place);
        const std::uint64_t hash_b = placeHash(points[b].place);
        return hash_a != hash_b ? hash_a < hash_b : a < b;
      });
    }
    for (auto it = begin; it != keep; ++it) selected_[*it] = 1;
  }

  // Two-pointer partition carrying the flags along with the points.
  std::size_t front = 0, back = points.size();
  while (front < back) {
    if (selected_[front]) {
      ++front;
    } else {
      --back;
      std::swap(points[front], points[back]);
      std::swap(selected_[front], selected_[back]);
    }
  }
  return front;
}

std::array<std::vector<GridPlace>, 8> NodeIndexer::coarserForChildren(const CellKey& key,
                                                                      std::span<const GridPlace> coarser,
                                                                      std::span<const BuildPoint> selected) const {
  std::array<std::vector<GridPlace>, 8> result;
  for (const GridPlace& p : coarser) result[static_cast<std::size_t>(octantOf(key, p))].push_back(p);
  for (const BuildPoint& b : selected) result[static_cast<std::size_t>(octantOf(key, b.place))].push_back(b.place);
  return result;
}

std::array<std::size_t, 9> NodeIndexer::splitByOctant(const CellKey& key, std::span<BuildPoint> points) {
  octants_.resize(points.size());
  std::array<std::size_t, 8> counts{};
  for (std::size_t i = 0; i < points.size(); ++i) {
    octants_[i] = static_cast<std::uint8_t>(octantOf(key, points[i].place));
    ++counts[octants_[i]];
  }
  std::array<std::size_t, 9> bounds{};
  for (std::size_t o = 0; o < 8; ++o) bounds[o + 1] = bounds[o] + counts[o];
  // In-place cycle sort into the eight ranges (American flag sort), the octants moving along.
  std::array<std::size_t, 8> next{};
  for (std::size_t o = 0; o < 8; ++o) next[o] = bounds[o];
  for (std::size_t o = 0; o < 8; ++o) {
    while (next[o] < bounds[o + 1]) {
      const std::size_t target = octants_[next[o]];
      if (target == o) {
        ++next[o];
      } else {
        const std::size_t to = next[target]++;
        std::swap(points[next[o]], points[to]);
        std::swap(octants_[next[o]], octants_[to]);
      }
    }
  }
  return bounds;
}

std::pair<std::size_t, std::uint8_t> NodeIndexer::keepSubsampleAndIndexChildren(const CellKey& key,
                                                                                std::span<BuildPoint> points,
                                                                                std::span<const GridPlace> coarser,
                                                                                const ChildIndexer& index_child) {
  const std::size_t kept = selectSubsample(key, points, coarser);
  const std::span<BuildPoint> rest = points.subspan(kept);
  const auto bounds = splitByOctant(key, rest);
  const auto child_coarser = coarserForChildren(key, coarser, points.first(kept));
  std::uint8_t mask = 0;
  for (int o = 0; o < 8; ++o) {
    const auto index = static_cast<std::size_t>(o);
    const auto range = rest.subspan(bounds[index], bounds[index + 1] - bounds[index]);
    if (index_child(key.child(o), range, child_coarser[index])) mask = static_cast<std::uint8_t>(mask | (1u << o));
  }
  return {kept, mask};
}

bool NodeIndexer::indexSubtree(const CellKey& key, std::span<BuildPoint> points, std::span<const GridPlace> coarser,
                               const NodeSink& sink) {
  if (points.empty()) return false;
  if (isLeaf(key, points.size())) {
    sink(key, points, 0);
    return true;
  }
  const auto [kept, mask] = keepSubsampleAndIndexChildren(
      key, points, coarser, [&](const CellKey& child, std::span<BuildPoint> range, std::span<const GridPlace> above) {
        return indexSubtree(child, range, above, sink);
      });
  sink(key, points.first(kept), mask);
  return true;
}

StopSet::StopSet(const std::vector<CellKey>& roots) : stops(roots.begin(), roots.end()) {
  for (const CellKey& root : roots) {
    for (auto parent = root.parent(); parent; parent = parent->parent()) {
      if (!ancestors.insert(*parent).second) break;  // the rest of the path is in already
    }
  }
}

bool NodeIndexer::indexAbove(const CellKey& key, std::span<BuildPoint> points, std::span<const GridPlace> coarser,
                             const StopSet& stops, const StopSink& stop_sink, const NodeSink& sink) {
  if (stops.stops.contains(key)) return stop_sink(key, points);
  if (!stops.ancestors.contains(key)) {
    assert(points.empty() && "points outside every indexed subtree");
    return false;
  }
  const auto [kept, mask] = keepSubsampleAndIndexChildren(
      key, points, coarser, [&](const CellKey& child, std::span<BuildPoint> range, std::span<const GridPlace> above) {
        return indexAbove(child, range, above, stops, stop_sink, sink);
      });
  if (kept == 0 && mask == 0) return false;  // everything below was taken further up
  sink(key, points.first(kept), mask);
  return true;
}

}  // namespace plumb::lod
