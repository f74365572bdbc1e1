// Per-node grid subsampling and the recursive split into children.
//
//   1. A node with at most leaf_max_points points, or at a level whose cells are smaller than
//      kMinCellSize, is a leaf: it keeps all its points.
//   2. Otherwise, mark the cells of the 128^3 grid over the node that hold a point of a coarser
//      level; in every other occupied grid cell keep the point of the smallest position hash
//      (ties, i.e. duplicates: the earlier point), and move those points to the front.
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
constexpr std::uint32_t kTaken = kEmpty - 1;  // holds a point of a coarser level
constexpr std::size_t kGridCells = std::size_t{kSamplingGrid} * kSamplingGrid * kSamplingGrid;
// A pseudo-random number in [0, 1) from the bits of a position (splitmix64 finaliser): the same
// point scores the same whatever the order of the input or the chunking of the build.
double positionScore(const Position& p) {
  std::uint64_t h = 0x9E3779B97F4A7C15ULL;
  for (const double c : p) {
    std::uint64_t bits = 0;
    std::memcpy(&bits, &c, sizeof bits);
    h ^= bits + 0x9E3779B97F4A7C15ULL + (h << 6) + (h >> 2);
    h = (h ^ (h >> 30)) * 0xBF58476D1CE4E5B9ULL;
    h = (h ^ (h >> 27)) * 0x94D049BB133111EBULL;
    h ^= h >> 31;
  }
  return static_cast<double>(h >> 11) * 0x1.0p-53;
}

// Below a tenth of a millimetre a node stops splitting: its points are as good as duplicates.
constexpr double kMinCellSize = 1e-4 * kSamplingGrid;

}  // namespace

NodeIndexer::NodeIndexer(const Cube& cube, std::uint32_t leaf_max_points)
    : cube_(cube), leaf_max_points_(leaf_max_points) {}

bool NodeIndexer::isLeaf(const CellKey& key, std::size_t count) const {
  return count <= leaf_max_points_ || key.level >= kMaxLevel || cube_.cellSize(key.level) < kMinCellSize;
}

std::size_t NodeIndexer::selectSubsample(const CellKey& key, std::span<BuildPoint> points,
                                         std::span<const Position> coarser) {
  if (best_index_.empty()) {
    best_index_.assign(kGridCells, kEmpty);
    best_score_.assign(kGridCells, 0.0f);
  }
  const Box3 box = cube_.cellBox(key);
  const double inverse_step = kSamplingGrid / cube_.cellSize(key.level);
  // Which point of a grid cell stands for it: the one whose position hashes lowest, a choice
  // independent of where in the cell the point lies. Any geometric rule (nearest the cell's
  // centre, or its lower corner) prefers, on a noisy wall, the points on one side of the wall, and
  // biases every plane fitted to a coarse level by a good fraction of the noise, more so the more
  // points compete for a cell (docs/octree-format.md).
  auto locate = [&](const Position& p) {
    std::size_t cell = 0;
    for (std::size_t a = 0; a < 3; ++a) {
      const double local = (p[a] - box.min[a]) * inverse_step;
      const double index = std::clamp(std::floor(local), 0.0, double{kSamplingGrid - 1});
      cell = cell * kSamplingGrid + static_cast<std::size_t>(index);
    }
    return cell;
  };

  touched_.clear();
  for (const Position& p : coarser) {
    const std::size_t cell = locate(p);
    if (best_index_[cell] == kEmpty) touched_.push_back(static_cast<std::uint32_t>(cell));
    best_index_[cell] = kTaken;
  }
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Position p{points[i].x, points[i].y, points[i].z};
    const std::size_t cell = locate(p);
    const auto d = static_cast<float>(positionScore(p));
    const std::uint32_t best = best_index_[cell];
    if (best == kTaken) continue;
    if (best == kEmpty) {
      touched_.push_back(static_cast<std::uint32_t>(cell));
    } else if (!(d < best_score_[cell])) {
      continue;
    }
    best_index_[cell] = static_cast<std::uint32_t>(i);
    best_score_[cell] = d;
  }
  selected_.assign(points.size(), 0);
  for (std::uint32_t cell : touched_) {
    if (best_index_[cell] != kTaken) selected_[best_index_[cell]] = 1;
    best_index_[cell] = kEmpty;  // leave the scratch clean for the next node
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

int NodeIndexer::octantOf(const CellKey& key, const Position& p) const {
  // The same rule as Cube::cellAt at the child level, so a point's child is the cell it lies in.
  const CellKey first = key.child(0);
  const CellKey cell = cube_.cellAt(p, first.level);
  return static_cast<int>((cell.x - first.x) | ((cell.y - first.y) << 1) | ((cell.z - first.z) << 2));
}

std::array<std::vector<Position>, 8> NodeIndexer::coarserForChildren(const CellKey& key,
                                                                     std::span<const Position> coarser,
                                                                     std::span<const BuildPoint> selected) const {
  std::array<std::vector<Position>, 8> result;
  for (const Position& p : coarser) result[static_cast<std::size_t>(octantOf(key, p))].push_back(p);
  for (const BuildPoint& b : selected) {
    const Position p{b.x, b.y, b.z};
    result[static_cast<std::size_t>(octantOf(key, p))].push_back(p);
  }
  return result;
}

std::array<std::size_t, 9> NodeIndexer::splitByOctant(const CellKey& key, std::span<BuildPoint> points) {
  octants_.resize(points.size());
  std::array<std::size_t, 8> counts{};
  for (std::size_t i = 0; i < points.size(); ++i) {
    octants_[i] = static_cast<std::uint8_t>(octantOf(key, {points[i].x, points[i].y, points[i].z}));
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
                                                                                std::span<const Position> coarser,
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

bool NodeIndexer::indexSubtree(const CellKey& key, std::span<BuildPoint> points, std::span<const Position> coarser,
                               const NodeSink& sink) {
  if (points.empty()) return false;
  if (isLeaf(key, points.size())) {
    sink(key, points, 0);
    return true;
  }
  const auto [kept, mask] = keepSubsampleAndIndexChildren(
      key, points, coarser, [&](const CellKey& child, std::span<BuildPoint> range, std::span<const Position> above) {
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

bool NodeIndexer::indexAbove(const CellKey& key, std::span<BuildPoint> points, std::span<const Position> coarser,
                             const StopSet& stops, const StopSink& stop_sink, const NodeSink& sink) {
  if (stops.stops.contains(key)) return stop_sink(key, points);
  if (!stops.ancestors.contains(key)) {
    assert(points.empty() && "points outside every indexed subtree");
    return false;
  }
  const auto [kept, mask] = keepSubsampleAndIndexChildren(
      key, points, coarser, [&](const CellKey& child, std::span<BuildPoint> range, std::span<const Position> above) {
        return indexAbove(child, range, above, stops, stop_sink, sink);
      });
  if (kept == 0 && mask == 0) return false;  // everything below was taken further up
  sink(key, points.first(kept), mask);
  return true;
}

}  // namespace plumb::lod
