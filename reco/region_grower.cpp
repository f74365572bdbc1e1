// Seeded incremental region growing, paper section 3.5 (the seed of 3.4 included).
//
//   1. Level: the octree level whose spacing matches the wanted density d.
//   2. Seed: the points of that level within r_s of the picked point; up to three planes by
//      RANSAC (seed_planes.h); each starts a regression with its inliers.
//   3. Loop over a queue of level-L cells, nearest to the seed first. A cell holds the points
//      of levels 0..L in it (lod::pointsInCell). Its frontier is the assigned points within r
//      of it; breadth-first from the frontier, an unassigned point within r of an assigned one
//      joins the segment with the nearest plane among those within t_p whose points are within r
//      of it (a point joins at most one segment). New points extend the frontier, also into the
//      neighbouring cells they are within r of, which are queued (again) for processing.
//   4. After a cell that added points, refit the grown planes and publish a snapshot.
//   5. Stop when the queue is empty (converged) or the cancel flag is set (checked per cell).
//   6. Intersect the segments for their edges and corners (edges_and_corners.h).

#include "reco/region_grower.h"

#include <chrono>
#include <cmath>
#include <optional>
#include <queue>
#include <unordered_map>
#include <unordered_set>

#include "engine/lod/lod_query.h"
#include "reco/seed_planes.h"

namespace plumb::reco {
namespace {

using Clock = std::chrono::steady_clock;
using lod::CellKey;

// Integer grid coordinates of a position relative to an origin, packed into one key.
struct GridKey {
  std::int64_t x, y, z;
  bool operator==(const GridKey&) const = default;
};
struct GridKeyHash {
  std::size_t operator()(const GridKey& k) const {
    return static_cast<std::size_t>((static_cast<std::uint64_t>(k.x) * 73856093ULL) ^
                                    (static_cast<std::uint64_t>(k.y) * 19349663ULL) ^
                                    (static_cast<std::uint64_t>(k.z) * 83492791ULL));
  }
};

// A uniform grid of cell size `step` over positions near `origin` (kept small: UTM coordinates
// divided by a few centimetres would still fit, but relative ones keep the hash well spread).
class Grid {
 public:
  Grid(const Eigen::Vector3d& origin, double step) : origin_(origin), inverse_(1.0 / step) {}
  GridKey keyOf(const Eigen::Vector3d& p) const {
    const Eigen::Vector3d g = (p - origin_) * inverse_;
    return {static_cast<std::int64_t>(std::floor(g.x())), static_cast<std::int64_t>(std::floor(g.y())),
            static_cast<std::int64_t>(std::floor(g.z()))};
  }
  // Calls visit(key) for the 27 grid cells around p's cell: all that can hold points within
  // one step of p.
  template <typename Visit>
  void forEachAround(const Eigen::Vector3d& p, Visit&& visit) const {
    const GridKey k = keyOf(p);
    for (std::int64_t dz = -1; dz <= 1; ++dz) {
      for (std::int64_t dy = -1; dy <= 1; ++dy) {
        for (std::int64_t dx = -1; dx <= 1; ++dx) visit(GridKey{k.x + dx, k.y + dy, k.z + dz});
      }
    }
  }

 private:
  Eigen::Vector3d origin_;
  double inverse_;
};

struct Assigned {
  Eigen::Vector3d position;
  std::uint32_t segment;
};

struct CellState {
  std::vector<Eigen::Vector3d> points;
  std::vector<std::uint8_t> assigned;
  std::unordered_map<GridKey, std::vector<std::uint32_t>, GridKeyHash> by_grid;  // unassigned and assigned
  std::vector<Assigned> frontier;  // assigned points within r of this cell, not yet expanded here
};

class Grower {
 public:
  Grower(lod::NodeCache& cache, const GrowParameters& parameters, const GrowOptions& options,
         const GrowProgress& progress)
      : cache_(cache),
        octree_(cache.octree()),
        parameters_(parameters),
        options_(options),
        progress_(progress),
        radius_(parameters.search_radius_m),
        grid_(parameters.seed, parameters.search_radius_m),
        start_(Clock::now()) {
    snapshot_.level = octree_.levelForSpacing(parameters.spacing_m);
  }

  GrowSnapshot run() {
    seed();
    while (!queue_.empty()) {
      if (options_.cancel != nullptr && options_.cancel->load()) {
        snapshot_.cancelled = true;
        return finish(false);
      }
      const CellKey key = queue_.top().second;
      queue_.pop();
      queued_.erase(key);
      if (processCell(key)) publish();
    }
    return finish(true);
  }

 private:
  std::array<double, 3> array(const Eigen::Vector3d& p) const { return {p.x(), p.y(), p.z()}; }

  CellState& cell(const CellKey& key) {
    auto [it, inserted] = cells_.try_emplace(key);
    if (inserted) {
      for (const auto& p : lod::pointsInCell(cache_, key)) {
        const Eigen::Vector3d position(p[0], p[1], p[2]);
        it->second.by_grid[grid_.keyOf(position)].push_back(static_cast<std::uint32_t>(it->second.points.size()));
        it->second.points.push_back(position);
      }
      it->second.assigned.assign(it->second.points.size(), 0);
    }
    return it->second;
  }

  void enqueue(const CellKey& key) {
    if (!queued_.insert(key).second) return;
    queue_.push({octree_.cube().squaredDistance(key, array(parameters_.seed)), key});
  }

  // The level-L cells within r of p: its own and those whose faces are nearer than r.
  std::vector<CellKey> cellsNear(const Eigen::Vector3d& p) const {
    std::vector<CellKey> keys;
    for (int dz = -1; dz <= 1; ++dz) {
      for (int dy = -1; dy <= 1; ++dy) {
        for (int dx = -1; dx <= 1; ++dx) {
          const Eigen::Vector3d q = p + radius_ * Eigen::Vector3d(dx, dy, dz);
          const CellKey key = octree_.cube().cellAt(array(q), snapshot_.level);
          if (std::find(keys.begin(), keys.end(), key) == keys.end()) keys.push_back(key);
        }
      }
    }
    return keys;
  }

  // Records p as assigned to `segment`: it joins the regression and every nearby cell's frontier.
  void assign(CellState& state, std::uint32_t index, std::uint32_t segment) {
    state.assigned[index] = 1;
    const Eigen::Vector3d& p = state.points[index];
    regressions_[segment].add(p);
    segment_points_[segment].push_back(p);
    assigned_[grid_.keyOf(p)].push_back({p, segment});
    grown_[segment] = true;
    // The plane follows the regression as it grows (the paper tests each point against the
    // current regression): refit whenever the support has grown by a tenth, so a seed plane
    // from a few points straightens out long before its error matters, at O(log n) refits.
    if (regressions_[segment].count() >= fitted_count_[segment] + fitted_count_[segment] / 10 + 8) refit(segment);
    for (const CellKey& key : cellsNear(p)) {
      if (processing_ && key == *processing_) continue;  // its breadth-first queue has p already
      cell(key).frontier.push_back({p, segment});
      enqueue(key);
    }
  }

  void seed() {
    const double rs = parameters_.seed_radius_m;
    const auto seed_array = array(parameters_.seed);
    const CellKey low =
        octree_.cube().cellAt({seed_array[0] - rs, seed_array[1] - rs, seed_array[2] - rs}, snapshot_.level);
    const CellKey high =
        octree_.cube().cellAt({seed_array[0] + rs, seed_array[1] + rs, seed_array[2] + rs}, snapshot_.level);
    std::vector<Eigen::Vector3d> points;
    std::vector<std::pair<CellKey, std::uint32_t>> origin;
    for (std::uint32_t z = low.z; z <= high.z; ++z) {
      for (std::uint32_t y = low.y; y <= high.y; ++y) {
        for (std::uint32_t x = low.x; x <= high.x; ++x) {
          const CellKey key{snapshot_.level, x, y, z};
          if (octree_.cube().squaredDistance(key, seed_array) > rs * rs) continue;
          CellState& state = cell(key);
          for (std::uint32_t i = 0; i < state.points.size(); ++i) {
            if ((state.points[i] - parameters_.seed).squaredNorm() <= rs * rs) {
              points.push_back(state.points[i]);
              origin.emplace_back(key, i);
            }
          }
        }
      }
    }
    SeedOptions seed_options;
    seed_options.threshold = parameters_.plane_threshold_m;
    seed_options.max_planes = options_.max_planes;
    seed_options.drop_unstable = options_.drop_unstable;
    seed_options.seed = options_.random_seed;
    const std::vector<SeedPlane> planes = findSeedPlanes(points, seed_options);
    regressions_.resize(planes.size());
    planes_.resize(planes.size());
    fitted_count_.assign(planes.size(), 0);
    segment_points_.resize(planes.size());
    grown_.assign(planes.size(), false);
    for (std::uint32_t s = 0; s < planes.size(); ++s) {
      planes_[s] = planes[s].plane;  // the RANSAC refit, until the regression takes over
      for (std::uint32_t i : planes[s].inliers) assign(cell(origin[i].first), origin[i].second, s);
      refit(s);
    }
    snapshot_.points_tested += points.size();
    if (!planes.empty()) publish();
  }

  // The segment an unassigned point p joins: the nearest plane within t_p among the segments
  // with an assigned point within r of p; -1 for none.
  int bestSegment(const Eigen::Vector3d& p) {
    int best = -1;
    double best_distance = parameters_.plane_threshold_m;
    std::uint32_t seen_mask = 0;
    grid_.forEachAround(p, [&](const GridKey& key) {
      const auto it = assigned_.find(key);
      if (it == assigned_.end()) return;
      for (const Assigned& a : it->second) {
        if ((seen_mask >> a.segment) & 1u) continue;
        if ((a.position - p).squaredNorm() > radius_ * radius_) continue;
        seen_mask |= 1u << a.segment;
        ++snapshot_.points_tested;
        const Plane& plane = planes_[a.segment];
        if (!plane.valid) continue;
        const double d = plane.distance(p);
        if (d < best_distance) {
          best_distance = d;
          best = static_cast<int>(a.segment);
        }
      }
    });
    return best;
  }

  // Breadth-first from the cell's frontier; returns whether any point was added.
  bool processCell(const CellKey& key) {
    ++snapshot_.cells_visited;
    processing_ = key;
    CellState& state = cell(key);
    std::vector<Assigned> queue = std::move(state.frontier);
    state.frontier.clear();
    bool added = false;
    for (std::size_t next = 0; next < queue.size(); ++next) {
      const Assigned from = queue[next];
      grid_.forEachAround(from.position, [&](const GridKey& grid_key) {
        const auto it = state.by_grid.find(grid_key);
        if (it == state.by_grid.end()) return;
        for (std::uint32_t i : it->second) {
          if (state.assigned[i]) continue;
          const double distance = (state.points[i] - from.position).norm();
          if (distance > radius_) continue;
          const int segment = bestSegment(state.points[i]);
          if (segment < 0) continue;
          // assign() may add to this cell's frontier too; the local queue carries on instead.
          assign(state, i, static_cast<std::uint32_t>(segment));
          queue.push_back({state.points[i], static_cast<std::uint32_t>(segment)});
          neighbour_distance_sum_ += distance;
          ++neighbour_distance_count_;
          added = true;
        }
      });
    }
    processing_.reset();
    if (added) {
      for (std::uint32_t s = 0; s < regressions_.size(); ++s) {
        if (grown_[s]) refit(s);
        grown_[s] = false;
      }
    }
    return added;
  }

  void refit(std::uint32_t segment) {
    planes_[segment] = regressions_[segment].fit();
    fitted_count_[segment] = regressions_[segment].count();
  }

  void fillSnapshot() {
    snapshot_.segments.clear();
    for (std::size_t s = 0; s < regressions_.size(); ++s) {
      snapshot_.segments.push_back({planes_[s], regressions_[s].count()});
    }
    snapshot_.mean_neighbour_distance =
        neighbour_distance_count_ > 0 ? neighbour_distance_sum_ / static_cast<double>(neighbour_distance_count_) : 0.0;
    snapshot_.elapsed_ms = std::chrono::duration<double, std::milli>(Clock::now() - start_).count();
  }

  void publish() {
    fillSnapshot();
    if (progress_) progress_(snapshot_);
  }

  GrowSnapshot finish(bool converged) {
    snapshot_.converged = converged;
    fillSnapshot();
    std::vector<SegmentGeometry> geometry;
    for (std::size_t s = 0; s < regressions_.size(); ++s) geometry.push_back({planes_[s], segment_points_[s]});
    FeatureOptions features;
    features.search_radius = radius_;
    Features found = findEdgesAndCorners(geometry, features);
    snapshot_.edges = std::move(found.edges);
    snapshot_.corners = std::move(found.corners);
    return snapshot_;
  }

  lod::NodeCache& cache_;
  const lod::Octree& octree_;
  GrowParameters parameters_;
  GrowOptions options_;
  const GrowProgress& progress_;
  double radius_;
  Grid grid_;
  Clock::time_point start_;

  GrowSnapshot snapshot_;
  std::vector<PlaneRegression> regressions_;
  std::vector<Plane> planes_;                                 // the regressions' planes, refitted as they grow
  std::vector<std::uint64_t> fitted_count_;                   // regression size at the last refit
  std::vector<std::vector<Eigen::Vector3d>> segment_points_;  // for the edges and corners
  std::vector<bool> grown_;
  std::unordered_map<CellKey, CellState, lod::CellKeyHash> cells_;
  std::unordered_map<GridKey, std::vector<Assigned>, GridKeyHash> assigned_;
  std::priority_queue<std::pair<double, CellKey>, std::vector<std::pair<double, CellKey>>, std::greater<>> queue_;
  std::unordered_set<CellKey, lod::CellKeyHash> queued_;
  std::optional<CellKey> processing_;  // the cell whose breadth-first search is running
  double neighbour_distance_sum_ = 0.0;
  std::uint64_t neighbour_distance_count_ = 0;
};

}  // namespace

GrowSnapshot growRegions(lod::NodeCache& cache, const GrowParameters& parameters, const GrowOptions& options,
                         const GrowProgress& progress) {
  return Grower(cache, parameters, options, progress).run();
}

}  // namespace plumb::reco
