// Seeded incremental region growing, paper section 3.5 (the seed of 3.4 and the adaptive
// resolution of 3.6 included).
//
//   1. Level: the octree level whose spacing matches the wanted density d.
//   2. Seed: the points of that level within r_s of the picked point; up to three planes by
//      RANSAC (seed_planes.h); each starts a regression with its inliers.
//   3. Loop over a queue of cells, nearest to the seed first. A cell of level L holds the points
//      of levels 0..L in it (lod::pointsInCell). Its frontier is the assigned points within r
//      of it; breadth-first from the frontier, an unassigned point within r of an assigned one
//      joins the segment with the nearest plane among those within t_p whose points are within r
//      of it (a point joins at most one segment), where the surface around it continues the
//      segment's (continuesSurface). New points extend the frontier, also into the
//      neighbouring cells they are within r of, which are claimed and queued (again).
//   4. Adaptive resolution, as a cell leaves the queue: where the observed density is below
//      refine_below x d and the octree has finer points, the cell is replaced by its children.
//      Where it is above coarsen_above x d, the level is locked: the cells inside the parents of
//      the cells claimed so far are finished at that level (mark), the others wait; then those
//      that wait move to their parents if the density is still too high (finish). Points are
//      octree identities (lod::PointRef), so a point met again at another level is known.
//   5. After a cell that added points, refit the grown planes and publish a snapshot: planes,
//      outlines (outline.h) and the edges and corners between the segments (edges_and_corners.h),
//      the last two redrawn as the segments grow by a quarter.
//   6. When the queue is empty, each segment may bridge a gap wider than r (bridgeGaps): the free
//      points on its plane within r_s / 2 of it join, and the loop goes on from them. Stop when
//      no bridge finds anything (converged) or the cancel flag is set (checked per cell).
//   7. Settle (converged grows): points near where segments meet move to the nearest plane
//      among the segments around them, and the planes are refitted.
//   8. Refine (converged grows): each plane's final fit is a robust M-estimate over the points
//      around its segment (robust_plane_fit.h), which may take in points the growth turned away
//      and give up others, and then a least-squares fit where the points lie away from the
//      segment's border (interior_points.h); the final result has everything drawn anew.
//
// The stages live in files of their own (grower.h lists them); this one holds the loop.

#include "reco/region_grower.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <span>
#include <unordered_map>
#include <utility>

#include "reco/grower.h"
#include "reco/noise_threshold.h"
#include "reco/outline.h"
#include "reco/point_spacing.h"

namespace plumb::reco {
namespace detail {
namespace {

// How a snapshot draws a segment's outline and the edges and corners between segments, for a
// grow whose search radius is `radius`: the outline's alpha is r (its raster half that), and
// points within 2r of a line or corner count as near it.
std::shared_ptr<const PlaneOutline> drawOutline(const Plane& plane, std::span<const Eigen::Vector3d> points,
                                                double radius) {
  OutlineOptions outline;
  outline.alpha_m = radius;
  outline.cell_m = radius / 2.0;
  return std::make_shared<const PlaneOutline>(outlineOnPlane(plane, points, outline));
}

Features drawFeatures(std::span<const SegmentGeometry> segments, double radius) {
  FeatureOptions features;
  features.search_radius = radius;
  return findEdgesAndCorners(segments, features);
}

// The grid of the segments' points (Grower::assigned_) for a search radius: cells twice as wide,
// so that the 8 nearest a point hold every segment point within the radius (forEachNear).
PointGrid segmentGrid(const Eigen::Vector3d& seed, double radius) {
  return PointGrid(seed, 2.0 * radius);
}

}  // namespace

Grower::Grower(lod::NodeCache& cache, const GrowParameters& parameters, const GrowOptions& options,
               const GrowProgress& progress)
    : octree_(cache.octree()),
      cell_points_(cache),
      parameters_(parameters),
      options_(options),
      progress_(progress),
      radius_(parameters.search_radius_m),
      grid_(segmentGrid(parameters.seed, parameters.search_radius_m)),
      claims_(octree_.cube()),
      membership_(octree_),
      start_(Clock::now()) {
  base_level_ = octree_.levelForSpacing(parameters.spacing_m);
  snapshot_.level = base_level_;
  snapshot_.finest_level = snapshot_.coarsest_level = base_level_;
  working_level_ = base_level_;
}

GrowSnapshot Grower::run() {
  seed();
  for (;;) {
    if (queue_.empty()) {
      if (locked_level_) {
        unlockLevel();
        continue;
      }
      if (bridgeGaps()) continue;
      break;
    }
    if (options_.cancel != nullptr && options_.cancel->load()) {
      snapshot_.cancelled = true;
      return finish(false);
    }
    const CellKey key = queue_.top().second;
    queue_.pop();
    queued_.erase(key);
    if (!claims_.claimed(key)) continue;  // replaced by its children or parent since it was queued
    if (adapt(key)) continue;
    if (processCell(key)) publish();
  }
  return finish(true);
}

// Section 3.7: r is twice the mean point spacing. The spacing d asks for is what the octree
// gives where the scan is dense enough; where it is sparser (a distant wall, or --detail full,
// which asks for the deepest level's spacing), the points are farther apart than d implies and
// a search radius of twice d's spacing finds no neighbours. The seed points tell the spacing the
// data has: the median nearest-neighbour distance, and each seed plane's areal spacing, which
// also sees the gaps between scan lines (point_spacing.h). r follows the largest, at most half
// of r_s. The density the grow aims for stays d: where the octree has finer points further on,
// the adaptive resolution goes and gets them.
void Grower::adaptToDataSpacing(const std::vector<Eigen::Vector3d>& seed_points, const std::vector<SeedPlane>& planes) {
  double data_spacing = medianNearestDistance(seed_points, 0.5 * parameters_.seed_radius_m);
  std::vector<Eigen::Vector3d> inliers;
  for (const SeedPlane& plane : planes) {
    inliers.clear();
    for (std::uint32_t i : plane.inliers) inliers.push_back(seed_points[i]);
    data_spacing = std::max(data_spacing, arealSpacing(plane.plane, inliers));
  }
  snapshot_.data_spacing_m = data_spacing;
  const double reach = reachFor(data_spacing);
  if (reach > radius_) {
    radius_from_data_ = true;
    radius_ = std::min(reach, 0.5 * parameters_.seed_radius_m);
    grid_ = segmentGrid(parameters_.seed, radius_);
  }
  snapshot_.search_radius_m = radius_;
}

// The search radius for points `spacing` apart on a surface: twice the spacing, or wider where the
// noise measured at the seed spreads them into a slab thicker than that. A point then has about
// as many neighbours within the radius as within two spacings on a clean surface (4 pi): within
// a radius r well under the noise sigma, a slab holds 1.18 r^3 / (sigma s^2) of them (the offset
// between two points along the normal has sigma sqrt(2)), so r^3 = kSlabReach sigma s^2. At full
// detail on a 1 M-point room with 20 mm noise (s 3.5 mm) two spacings held one neighbour in
// five, and the growth fell apart.
double Grower::reachFor(double spacing) const {
  return std::max(2.0 * spacing, std::cbrt(kSlabReach * reach_sigma_ * spacing * spacing));
}

// The deepest level, not below `finest`, whose cells are at least `width` wide.
std::uint32_t Grower::cellLevelFor(double width, std::uint32_t finest) const {
  std::uint32_t level = finest;
  while (level > 0 && octree_.cube().cellSize(level) < width) --level;
  return level;
}

// The cells of `cell_level` that meet the seed sphere, in z, y, x order: every cell of the box
// around the sphere, also those without a node of their own.
std::vector<CellKey> Grower::seedCells(std::uint32_t cell_level) const {
  const double rs = parameters_.seed_radius_m;
  const auto seed_array = array(parameters_.seed);
  const CellKey low = octree_.cube().cellAt({seed_array[0] - rs, seed_array[1] - rs, seed_array[2] - rs}, cell_level);
  const CellKey high = octree_.cube().cellAt({seed_array[0] + rs, seed_array[1] + rs, seed_array[2] + rs}, cell_level);
  std::vector<CellKey> cells;
  for (std::uint32_t z = low.z; z <= high.z; ++z) {
    for (std::uint32_t y = low.y; y <= high.y; ++y) {
      for (std::uint32_t x = low.x; x <= high.x; ++x) {
        const CellKey key{cell_level, x, y, z};
        if (octree_.cube().squaredDistance(key, seed_array) <= rs * rs) cells.push_back(key);
      }
    }
  }
  return cells;
}

// Claims the seed cells of `cell_level` (seedCells), each holding the points of levels down to
// point_levels_ finer, and gathers the points inside the sphere with where they lie. Where a
// branch ends in a leaf above the level, a cell's points come from its ancestors. `cell_level`
// becomes the grow's base and working level (the level its cells are claimed at from then on).
void Grower::claimSeedCells(std::uint32_t cell_level, SeedSphere& sphere) {
  const double rs = parameters_.seed_radius_m;
  base_level_ = working_level_ = cell_level;
  for (const CellKey& key : seedCells(cell_level)) {
    sphere.cells.push_back(key);
    claims_.claim(key);
    const CellState& state = loaded(key);
    for (std::uint32_t i = 0; i < state.points.size(); ++i) {
      if ((state.points[i] - parameters_.seed).squaredNorm() <= rs * rs) {
        sphere.points.push_back(state.points[i]);
        sphere.origin.emplace_back(key, i);
      }
    }
  }
}

// The gathered cells' points dealt out to the cells of the finer `cell_level` inside them,
// instead of gathered again (on a 100 M-point room that took half the seed's time): those cells
// that meet the seed sphere are claimed, loaded and indexed, each with the points and the order
// it would load with (pointsInCell: its own node's points, then its ancestors', nearest first,
// then its descendants' level by level), and inserted in the order claimSeedCells claims them,
// so that the grow is the one a second gather gave. sphere.origin follows its points.
void Grower::dealSeedCells(std::uint32_t cell_level, SeedSphere& sphere) {
  const double rs = parameters_.seed_radius_m;
  const lod::Cube& cube = octree_.cube();
  const std::uint32_t steps = cell_level - working_level_;  // the gathered cells' level to this one
  const std::uint32_t per_axis = 1u << steps;
  // Per gathered cell, where each of its points went: the dealt cell's number and the index there.
  std::unordered_map<CellKey, std::vector<std::pair<std::uint32_t, std::uint32_t>>, lod::CellKeyHash> moved;
  std::vector<std::pair<CellKey, CellState>> dealt;
  for (const CellKey& gathered_key : sphere.cells) {
    const CellState& gathered = cells_.at(gathered_key);
    const std::size_t n = gathered.points.size();
    // Each point's cell (the dense number of the cell inside the gathered one) and its rank in
    // that cell's order: 0 its own node, L - level an ancestor, level a descendant.
    std::vector<std::uint32_t> local(n);
    std::vector<std::uint32_t> rank(n);
    std::array<std::uint32_t, lod::kMaxLevel + 1> rank_count{};  // ranks 0..kMaxLevel
    for (std::size_t i = 0; i < n; ++i) {
      const CellKey& node = octree_.nodes()[gathered.refs[i].node].key;
      const CellKey cell = node.level >= cell_level
                               ? CellKey{cell_level, node.x >> (node.level - cell_level),
                                         node.y >> (node.level - cell_level), node.z >> (node.level - cell_level)}
                               : cube.cellAt(array(gathered.points[i]), cell_level);
      local[i] = ((cell.z - (gathered_key.z << steps)) * per_axis + (cell.y - (gathered_key.y << steps))) * per_axis +
                 (cell.x - (gathered_key.x << steps));
      rank[i] = node.level == cell_level ? 0 : node.level < cell_level ? cell_level - node.level : node.level;
      ++rank_count[rank[i]];
    }
    std::vector<std::uint32_t> by_rank(n);  // the points in rank order, stable
    std::uint32_t first = 0;
    for (std::uint32_t& count : rank_count) first += std::exchange(count, first);
    for (std::uint32_t i = 0; i < n; ++i) by_rank[rank_count[rank[i]]++] = i;

    std::vector<std::uint32_t> local_count(std::size_t{per_axis} * per_axis * per_axis, 0);
    for (const std::uint32_t l : local) ++local_count[l];
    std::vector<std::uint32_t> number(local_count.size(), 0);  // dealt number + 1, 0: none
    auto& places = moved[gathered_key];
    places.assign(n, {0, 0});
    for (std::uint32_t i : by_rank) {
      std::uint32_t& cell_number = number[local[i]];
      if (cell_number == 0) {
        const std::uint32_t lx = local[i] % per_axis;
        const std::uint32_t ly = local[i] / per_axis % per_axis;
        const std::uint32_t lz = local[i] / per_axis / per_axis;
        const CellKey key{cell_level, (gathered_key.x << steps) + lx, (gathered_key.y << steps) + ly,
                          (gathered_key.z << steps) + lz};
        if (cube.squaredDistance(key, array(parameters_.seed)) > rs * rs) continue;  // not claimed
        dealt.emplace_back(key, CellState{});
        dealt.back().second.reserve(local_count[local[i]]);
        cell_number = static_cast<std::uint32_t>(dealt.size());
      }
      CellState& state = dealt[cell_number - 1].second;
      places[i] = {cell_number - 1, static_cast<std::uint32_t>(state.points.size())};
      state.add(gathered.points[i], gathered.refs[i], gathered.assigned[i]);  // nothing is tested yet
    }
  }
  for (auto& [key, index] : sphere.origin) {
    const auto& [cell_number, dealt_index] = moved.at(key)[index];
    key = dealt[cell_number].first;
    index = dealt_index;
  }
  // Claimed and inserted as claimSeedCells does (seedCells: empty cells too, in its order;
  // cells_'s order is the final fit's).
  std::unordered_map<CellKey, std::uint32_t, lod::CellKeyHash> dealt_number;
  for (std::uint32_t d = 0; d < dealt.size(); ++d) dealt_number.emplace(dealt[d].first, d);
  forgetCells();
  sphere.cells = seedCells(cell_level);
  for (const CellKey& key : sphere.cells) {
    claims_.claim(key);
    CellState& state = cells_[key];
    if (const auto it = dealt_number.find(key); it != dealt_number.end()) state = std::move(dealt[it->second].second);
    state.loaded = true;
    indexCell(state);
  }
  base_level_ = working_level_ = cell_level;
}

// The deepest level, not below `finest`, whose spacing is at least r_s / kSeedSampleSpacings.
std::uint32_t Grower::seedSampleLevel(std::uint32_t finest) const {
  const double spacing = parameters_.seed_radius_m / kSeedSampleSpacings;
  std::uint32_t level = finest;
  while (level > 0 && octree_.spacing(level) < spacing) --level;
  return level;
}

// Drops every cell and claim (the seed gathers its sphere more than once).
void Grower::forgetCells() {
  cells_.clear();
  claims_ = CellClaims(octree_.cube());
}

// The seed planes, with t_p measured from the data where the parameters ask for it.
std::vector<SeedPlane> Grower::findPlanes(std::span<const Eigen::Vector3d> points, const SeedOptions& options) {
  snapshot_.points_tested += points.size();
  return parameters_.plane_threshold_from_data ? seedPlanesMeasuringThreshold(points, options)
                                               : findSeedPlanes(points, options);
}

// The seed planes found on the points of `sample_level` within r_s (gathered in cells of
// `cell_level`), published at once as a first snapshot: the planes, their outlines and the
// edges and corners between them. The cells are forgotten again.
std::vector<SeedPlane> Grower::seedFromSample(std::uint32_t sample_level, std::uint32_t cell_level,
                                              const SeedOptions& options) {
  point_levels_ = sample_level - cell_level;
  SeedSphere sample;
  claimSeedCells(cell_level, sample);
  std::vector<SeedPlane> planes = findPlanes(sample.points, options);
  forgetCells();
  if (planes.empty() || !progress_) return planes;

  const double reach = 2.0 * std::max(octree_.spacing(sample_level),
                                      medianNearestDistance(sample.points, 0.5 * parameters_.seed_radius_m));
  std::vector<std::vector<Eigen::Vector3d>> inliers(planes.size());
  snapshot_.segments.assign(planes.size(), {});
  std::vector<SegmentGeometry> geometry;
  for (std::size_t s = 0; s < planes.size(); ++s) {
    for (std::uint32_t i : planes[s].inliers) inliers[s].push_back(sample.points[i]);
    SegmentSnapshot& segment = snapshot_.segments[s];
    segment.plane = planes[s].plane;
    segment.points = inliers[s].size();
    segment.outline = drawOutline(planes[s].plane, inliers[s], reach);
    geometry.push_back({planes[s].plane, inliers[s]});
  }
  Features found = drawFeatures(geometry, reach);
  snapshot_.edges = std::move(found.edges);
  snapshot_.corners = std::move(found.corners);
  snapshot_.elapsed_ms = std::chrono::duration<double, std::milli>(Clock::now() - start_).count();
  progress_(snapshot_);
  return planes;
}

// The seed planes' points among `points`: within `threshold` of a plane, each given to the
// nearest. A plane left with fewer than three is dropped.
std::vector<SeedPlane> Grower::pointsOnPlanes(std::span<const Eigen::Vector3d> points,
                                              const std::vector<SeedPlane>& planes, double threshold) {
  std::vector<SeedPlane> result(planes.size());
  for (std::size_t s = 0; s < planes.size(); ++s) result[s].plane = planes[s].plane;
  for (std::uint32_t i = 0; i < points.size(); ++i) {
    std::size_t nearest = planes.size();
    double nearest_distance = threshold;
    for (std::size_t s = 0; s < planes.size(); ++s) {
      const double d = planes[s].plane.distance(points[i]);
      if (d < nearest_distance) {
        nearest_distance = d;
        nearest = s;
      }
    }
    if (nearest < planes.size()) result[nearest].inliers.push_back(i);
  }
  std::erase_if(result, [](const SeedPlane& plane) { return plane.inliers.size() < 3; });
  snapshot_.points_tested += points.size();
  return result;
}

// The seed (section 3.4). Cells are meant to be many times r wide (the neighbour search and the
// frontier work within a cell, and each cell visit has a cost of its own). At full detail r
// follows the data's spacing, tens of times the finest level's, and the cells of that level are
// only a few r wide: the grow spent its time passing the frontier between tiny cells (a 10 M-point
// room: 1.2 million cell visits). There the grow works in cells of a coarser level, each holding
// the points of every level down to the one d asks for (point_levels_ levels finer). The seed
// sphere is gathered in cells about r_s / 4 wide, before r is known, and claimed anew in cells
// of the right width once it is.
//
// Where d asks for points finer than r_s / kSeedSampleSpacings, the planes are found on a sample
// of the sphere at that spacing first and published at once (seedFromSample): at full detail on
// a 100 M-point room the cells around the sphere hold two million points, and gathering them
// took 0.5 to 1 s before anything showed. The sphere's points at d's spacing then go to those
// planes.
void Grower::seed() {
  const std::uint32_t point_level = base_level_;
  const std::uint32_t gather_level = cellLevelFor(0.25 * parameters_.seed_radius_m, point_level);
  const std::uint32_t sample_level = seedSampleLevel(point_level);
  SeedOptions seed_options;
  seed_options.threshold = parameters_.plane_threshold_m;
  seed_options.max_planes = std::min(options_.max_planes, kMaxSegments);
  seed_options.drop_unstable = options_.drop_unstable;
  seed_options.seed = options_.random_seed;
  seed_options.picked = parameters_.seed;
  const bool from_sample = sample_level < point_level;
  gathering_seed_ = true;
  std::vector<SeedPlane> planes;
  if (from_sample) planes = seedFromSample(sample_level, std::min(sample_level, gather_level), seed_options);
  SeedSphere sphere;
  point_levels_ = point_level - gather_level;
  claimSeedCells(gather_level, sphere);

  std::vector<Eigen::Vector3d>& points = sphere.points;
  planes =
      from_sample ? pointsOnPlanes(points, planes, parameters_.plane_threshold_m) : findPlanes(points, seed_options);
  snapshot_.plane_threshold_m = parameters_.plane_threshold_m;
  // A t_p given says nothing of the noise, and a reach of two spacings in a slab thicker than
  // that leaves the slab's outer points out (a 100 M-point room at 5 mm noise with --tp 0.015:
  // r 5.5 mm, 31.7 M points grown; with the noise measured, r 7.5 mm and 32.3 M). About
  // kReachNoiseResiduals of the inliers tell it within a percent.
  std::size_t inliers = 0;
  for (const SeedPlane& plane : planes) inliers += plane.inliers.size();
  reach_sigma_ = parameters_.plane_threshold_from_data
                     ? snapshot_.noise_sigma_m
                     : seedPlaneNoise(points, planes, parameters_.plane_threshold_m,
                                      std::max<std::size_t>(1, inliers / kReachNoiseResiduals));
  adaptToDataSpacing(points, planes);
  gathering_seed_ = false;
  const std::uint32_t cell_level = cellLevelFor(kMinCellRadii * radius_, point_level);
  if (options_.deal_seed_cells && cell_level > gather_level && cell_level - gather_level <= kMaxDealLevels) {
    point_levels_ = point_level - cell_level;
    dealSeedCells(cell_level, sphere);
  } else if (cell_level != gather_level) {
    // Claimed anew at the cell level; the inliers are found again by their identities.
    std::unordered_map<std::uint64_t, std::uint32_t> seed_index;  // point identity -> index in `points`
    for (std::uint32_t i = 0; i < sphere.origin.size(); ++i) {
      const auto& [key, index] = sphere.origin[i];
      seed_index.emplace(refKey(cells_[key].refs[index]), i);
    }
    forgetCells();
    point_levels_ = point_level - cell_level;
    SeedSphere claimed;
    claimSeedCells(cell_level, claimed);
    for (const auto& [key, index] : claimed.origin) {
      sphere.origin[seed_index.at(refKey(cells_[key].refs[index]))] = {key, index};
    }
  } else {
    // Loaded before r was known: their neighbour grids now.
    for (const CellKey& key : sphere.cells) indexCell(cells_[key]);
  }
  regressions_.resize(planes.size());
  planes_.resize(planes.size());
  fitted_count_.assign(planes.size(), 0);
  bridges_left_.assign(planes.size(), kMaxBridges);
  thresholds_.assign(planes.size(), parameters_.plane_threshold_m);
  segment_points_.resize(planes.size());
  segment_refs_.resize(planes.size());
  grown_.assign(planes.size(), false);
  for (std::uint32_t s = 0; s < planes.size(); ++s) {
    planes_[s] = planes[s].plane;  // the RANSAC refit, until the regression takes over
    updateThreshold(s);
    const CellKey* last_key = nullptr;  // an inlier's cell is most often the previous one's
    CellState* state = nullptr;
    for (std::uint32_t i : planes[s].inliers) {
      const auto& [key, index] = sphere.origin[i];
      if (last_key == nullptr || !(key == *last_key)) {
        last_key = &key;
        state = &cells_[key];
      }
      if (!state->assigned[index]) assign(key, *state, index, s);
    }
    refit(s);
  }
  if (!planes.empty()) publish();
  snapshot_.seeded_ms = std::chrono::duration<double, std::milli>(Clock::now() - start_).count();
}

// The noise of seed planes found within `window`: their inliers' residuals, pooled, leaving out
// those within the window of another plane (near a corner, the strips of the meeting surfaces).
// 0 with too few residuals to tell. `stride`: every stride-th inlier only.
double Grower::seedPlaneNoise(std::span<const Eigen::Vector3d> points, const std::vector<SeedPlane>& planes,
                              double window, std::size_t stride) const {
  std::vector<double> residuals;
  for (const SeedPlane& plane : planes) {
    for (std::size_t k = 0; k < plane.inliers.size(); k += stride) {
      const std::uint32_t i = plane.inliers[k];
      const bool near_another = std::any_of(planes.begin(), planes.end(), [&](const SeedPlane& other) {
        return &other != &plane && other.plane.distance(points[i]) < window;
      });
      if (!near_another) residuals.push_back(plane.plane.distance(points[i]));
    }
  }
  return residuals.size() >= kMinNoiseResiduals ? robustNoiseSigma(residuals, window) : 0.0;
}

// The seed planes with t_p from the data (noise_threshold.h), kThresholdSigmas times the noise:
//   1. The seed planes within the t_p given (20 mm by default) and the noise of their inliers
//      (seedPlaneNoise, corrected for the window's cut).
//   2. Where that noise is over 0.4 times the window, the window is too narrow to tell it (one
//      under twice the noise splits a wall into parallel slices, each with a fraction of the
//      noise): the planes again within 3 times it, up to three times.
//   3. The noise of patches a quarter of r_s wide (localNoiseSigma), which needs no window.
//      Both measures only err high, from what is not noise: the planes' from a door leaf in its
//      recess a few sigma behind a wall (30 mm noise: 43 mm), the patches' from edges and from
//      the two faces of a thin wall in one patch (2 mm noise: 46 mm). The noise is the least.
//   4. t_p is the larger of the t_p given and kThresholdSigmas times the noise: the noise raises
//      it, never lowers it. A real wall is not flat to its scanner's noise over metres: the NUIST
//      facade measures 2.1 mm of noise and 6.2 mm RMS over its 50 m^2; at 6 mm it stopped at
//      881 of its 17,724 points. Where t_p is tighter than the plane's spread, the grower's
//      inlier window follows the plane's RMS already (GrowOptions::noise_sigmas).
//   5. The planes again where t_p is a tenth or more off the window they were found in.
// Where too few points tell, t_p stays the parameters'.
std::vector<SeedPlane> Grower::seedPlanesMeasuringThreshold(std::span<const Eigen::Vector3d> points,
                                                            SeedOptions options) {
  std::vector<SeedPlane> planes = findSeedPlanes(points, options);
  double sigma = seedPlaneNoise(points, planes, options.threshold);
  for (int round = 0; round < 3 && sigma > 0.4 * options.threshold; ++round) {
    options.threshold = kThresholdSigmas * sigma;
    planes = findSeedPlanes(points, options);
    sigma = seedPlaneNoise(points, planes, options.threshold);
  }
  const double patches = localNoiseSigma(points, 0.25 * parameters_.seed_radius_m);
  if (patches > 0.0) sigma = sigma > 0.0 ? std::min(sigma, patches) : patches;
  if (!(sigma > 0.0)) return planes;
  snapshot_.noise_sigma_m = sigma;
  parameters_.plane_threshold_m = std::max(parameters_.plane_threshold_m, thresholdForNoise(sigma));
  if (std::abs(parameters_.plane_threshold_m - options.threshold) >= 0.1 * options.threshold) {
    options.threshold = parameters_.plane_threshold_m;
    planes = findSeedPlanes(points, options);
  }
  return planes;
}

// Fills the snapshot; outlines and features are redrawn where the segments have grown enough
// since they were last drawn (everything when `final`).
void Grower::fillSnapshot(bool final) {
  snapshot_.segments.resize(regressions_.size());
  outlined_count_.resize(regressions_.size(), 0);
  std::uint64_t total = 0;
  for (std::size_t s = 0; s < regressions_.size(); ++s) {
    SegmentSnapshot& segment = snapshot_.segments[s];
    segment.plane = planes_[s];
    segment.points = segment_points_[s].size();
    total += segment.points;
    if (!planes_[s].valid) {
      segment.outline.reset();
    } else if (final || segment.points >= outlined_count_[s] + outlined_count_[s] / 4 + 1) {
      segment.outline = drawOutline(planes_[s], segment_points_[s], radius_);
      outlined_count_[s] = segment.points;
    }
  }
  if (final || total >= featured_total_ + featured_total_ / 4 + 1) {
    std::vector<SegmentGeometry> geometry;
    for (std::size_t s = 0; s < regressions_.size(); ++s) geometry.push_back({planes_[s], segment_points_[s]});
    Features found = drawFeatures(geometry, radius_);
    snapshot_.edges = std::move(found.edges);
    snapshot_.corners = std::move(found.corners);
    featured_total_ = total;
  }
  snapshot_.mean_neighbour_distance =
      neighbour_distance_count_ > 0 ? neighbour_distance_sum_ / static_cast<double>(neighbour_distance_count_) : 0.0;
  snapshot_.front_spacing_m = front_spacing_;
  snapshot_.elapsed_ms = std::chrono::duration<double, std::milli>(Clock::now() - start_).count();
}

void Grower::publish() {
  fillSnapshot(false);
  if (progress_) progress_(snapshot_);
}

GrowSnapshot Grower::finish(bool converged) {
  if (converged && options_.settle) settle();
  if (converged && options_.refine_c > 0.0) refine();
  snapshot_.converged = converged;
  fillSnapshot(true);
  if (options_.collect_members) {
    auto members = membership_.members(regressions_.size());
    for (std::size_t s = 0; s < members.size(); ++s) snapshot_.segments[s].members = std::move(members[s]);
  }
  return snapshot_;
}

}  // namespace detail

GrowSnapshot growRegions(lod::NodeCache& cache, const GrowParameters& parameters, const GrowOptions& options,
                         const GrowProgress& progress) {
  return detail::Grower(cache, parameters, options, progress).run();
}

}  // namespace plumb::reco
