// The final fit of a converged grow (region_grower.cpp, steps 7 and 8): settling the points where
// segments meet on the nearest plane, then the robust fit of each plane (robust_plane_fit.h) with
// a last least-squares fit inside each segment (interior_points.h).

#include <cmath>

#include "reco/grower.h"
#include "reco/interior_points.h"
#include "reco/robust_plane_fit.h"

namespace plumb::reco::detail {

// Settles the points where segments meet: a point went to the first segment that reached it,
// but near an edge it may lie nearer the plane of the other one. Where one segment got there
// first along a whole edge, it holds a strip of its neighbour's points there, all on one side
// of its plane: a bias that grows with the noise. Each point moves to the nearest plane among
// those of the segments with a point within r of it and within their thresholds; then the
// regressions are rebuilt from their points.
void Grower::settle() {
  const std::size_t n = regressions_.size();
  if (n < 2) return;
  std::vector<std::vector<Eigen::Vector3d>> points(n);
  std::vector<std::vector<lod::PointRef>> refs(n);
  bool moved = false;
  for (std::uint32_t s = 0; s < n; ++s) {
    for (std::size_t i = 0; i < segment_points_[s].size(); ++i) {
      const Eigen::Vector3d& p = segment_points_[s][i];
      std::uint32_t best = s;
      double best_distance = planes_[s].valid ? planes_[s].distance(p) : INFINITY;
      const std::uint32_t near_mask = segmentsNear(p, 1u << s);
      for (std::uint32_t t = 0; t < n; ++t) {
        if (!((near_mask >> t) & 1u) || !planes_[t].valid) continue;
        const double d = planes_[t].distance(p);
        if (d < best_distance && d < thresholds_[t]) {
          best_distance = d;
          best = t;
        }
      }
      moved = moved || best != s;
      points[best].push_back(p);
      refs[best].push_back(segment_refs_[s][i]);
    }
  }
  if (!moved) return;
  for (std::uint32_t s = 0; s < n; ++s) {
    PlaneRegression regression;
    for (const Eigen::Vector3d& p : points[s]) regression.add(p);
    for (const lod::PointRef& ref : refs[s]) membership_.assign(ref, s);
    regressions_[s] = regression;
    refit(s);
  }
  segment_points_ = std::move(points);
  segment_refs_ = std::move(refs);
  rebuildAssigned();
}

// The neighbour grid of the segments' points anew, after they changed hands.
void Grower::rebuildAssigned() {
  assigned_.clear();
  for (std::uint32_t s = 0; s < segment_points_.size(); ++s) {
    for (const Eigen::Vector3d& p : segment_points_[s]) addToGrid(p, s);
  }
}

// The segments with a point within r of p, as a bit mask, taking those of `known` as near
// without looking (p's own segment, whose points fill the cells around it).
std::uint32_t Grower::segmentsNear(const Eigen::Vector3d& p, std::uint32_t known) const {
  std::uint32_t mask = known;
  grid_.forEachNear(p, [&](const GridKey& key) {
    const AssignedCell* cell = assigned_.find(key);
    if (cell == nullptr || (cell->segments & ~mask) == 0) return;
    for (const Assigned& a : cell->points) {
      if (!((mask >> a.segment) & 1u) && (a.position - p).squaredNorm() <= radius_ * radius_) mask |= 1u << a.segment;
    }
  });
  return mask;
}

// The segments that surround p: those whose points within r of it lie around it on their plane,
// not to one side (their mean, projected on the plane, is within kInsideOffset r of p), as bit
// mask. A point the growth turned away inside a segment is a tail of its noise; one beside
// the segment's border is as likely the strip of a surface that meets it there, the ceiling
// along a wall's top, all on one side of the plane.
std::uint32_t Grower::segmentsAround(const Eigen::Vector3d& p) const {
  std::array<Eigen::Vector3d, kMaxSegments> sum;
  sum.fill(Eigen::Vector3d::Zero());
  std::array<std::uint32_t, kMaxSegments> count{};
  std::uint32_t near = 0;
  grid_.forEachNear(p, [&](const GridKey& key) {
    const AssignedCell* cell = assigned_.find(key);
    if (cell == nullptr) return;
    for (const Assigned& a : cell->points) {
      if ((a.position - p).squaredNorm() > radius_ * radius_) continue;
      near |= 1u << a.segment;
      sum[a.segment] += a.position - p;
      ++count[a.segment];
    }
  });
  std::uint32_t inside = 0;
  for (std::uint32_t s = 0; s < regressions_.size(); ++s) {
    if (!((near >> s) & 1u) || count[s] < kMinAroundPoints || !planes_[s].valid) continue;
    const Eigen::Vector3d mean = sum[s] / static_cast<double>(count[s]);
    const Eigen::Vector3d along = mean - planes_[s].normal.dot(mean) * planes_[s].normal;
    if (along.norm() < kInsideOffset * radius_) inside |= 1u << s;
  }
  return inside;
}

// The robust final fit (robust_plane_fit.h). The pool: the segments' points, each with the
// segments near it, and the points of the processed cells that the growth tested and turned
// away, where they lie inside a segment (segmentsAround). Each
// round gives every pool point to the nearest plane, among the near segments', whose window
// (refine_c times that segment's robust scale) holds it, weighs it by the biweight and refits
// the planes; the scales follow the points each segment holds. The segments' points become those
// of positive weight: a point may join that the growth turned away, or leave. A last fit weighs
// the points inside each segment by 1.
void Grower::refine() {
  const std::size_t n = regressions_.size();
  struct PoolPoint {
    Eigen::Vector3d position;
    lod::PointRef ref;
    std::uint32_t near;  // bit s: the point may go to segment s (near it, or inside it)
  };
  std::vector<PoolPoint> pool;
  std::vector<double> scales(n, 0.0);
  for (std::uint32_t s = 0; s < n; ++s) {
    std::vector<double> residuals;
    for (std::size_t i = 0; i < segment_points_[s].size(); ++i) {
      const Eigen::Vector3d& p = segment_points_[s][i];
      pool.push_back({p, segment_refs_[s][i], segmentsNear(p, 1u << s)});
      if (planes_[s].valid) residuals.push_back(planes_[s].distance(p));
    }
    scales[s] = robustScale(std::move(residuals));
  }
  for (const auto& [key, state] : cells_) {
    if (!state.processed) continue;
    for (std::uint32_t i = 0; i < state.points.size(); ++i) {
      // A point never tested was never within r of a segment's point: not around any segment.
      if (state.assigned[i] || state.rejected_epoch[i] == kNeverTested) continue;
      const std::uint32_t inside = segmentsAround(state.points[i]);
      if (inside != 0) pool.push_back({state.points[i], state.refs[i], inside});
    }
  }

  std::vector<std::int8_t> owner(pool.size(), -1);
  std::vector<double> weights(pool.size(), 0.0);
  // The pool points each segment holds (positive weight), with their weights.
  struct Held {
    std::vector<Eigen::Vector3d> points;
    std::vector<double> weights;
  };
  const auto held = [&] {
    std::vector<Held> result(n);
    for (std::size_t i = 0; i < pool.size(); ++i) {
      if (owner[i] < 0 || !(weights[i] > 0.0)) continue;
      Held& segment = result[static_cast<std::size_t>(owner[i])];
      segment.points.push_back(pool[i].position);
      segment.weights.push_back(weights[i]);
    }
    return result;
  };
  for (std::uint32_t round = 0; round < options_.refine_rounds; ++round) {
    std::vector<std::vector<double>> residuals(n);
    for (std::size_t i = 0; i < pool.size(); ++i) {
      owner[i] = -1;
      weights[i] = 0.0;
      double best = INFINITY;
      for (std::uint32_t s = 0; s < n; ++s) {
        if (!((pool[i].near >> s) & 1u) || !planes_[s].valid) continue;
        const double d = planes_[s].distance(pool[i].position);
        const double window = options_.refine_c * scales[s];
        if (d < window && d < best) {
          best = d;
          owner[i] = static_cast<std::int8_t>(s);
          weights[i] = biweight(d, window);
        }
      }
      if (owner[i] >= 0) residuals[static_cast<std::size_t>(owner[i])].push_back(best);
    }
    const std::vector<Held> segments = held();
    for (std::uint32_t s = 0; s < n; ++s) {
      const Plane fitted = fitWeightedPlane(segments[s].points, segments[s].weights);
      if (!fitted.valid) continue;  // too few points left: the settled plane stays
      planes_[s] = fitted;
      scales[s] = robustScale(std::move(residuals[s]));
    }
  }

  // The last fit gives the points inside each segment full weight: there the biweight only
  // costs efficiency (86 %), while the strips of the surfaces that meet a plane, all on one
  // side of it, lie along its border, where the biweight's weights stay.
  //
  // The biweight holds the strips back but not to nothing: at full detail on a 1 M-point room
  // with 20 mm of noise, the walls passed the limit corner 0.4 to 1.8 mm off where the segments'
  // own points gave 0.3 at most. Near the border, within kBorderBandSigmas robust sigmas (a
  // strip's points project a few sigma either side of the edge, and the outline runs along the
  // outermost of them), the points of a cell whose neighbourhood lies to one side of the plane
  // are left out (interior_points.h, oneSidedBorderPoints). The test asks for an offset of a
  // quarter sigma as well as a significant one: a plane tilted a little by what the growth took
  // in (a door leaf in its recess) leaves the cells at its far ends a little off, and leaving
  // those out would lose the lever that holds the tilt back.
  std::vector<Held> members = held();
  for (std::uint32_t s = 0; s < n; ++s) {
    const BorderRaster raster = borderRaster(planes_[s], members[s].points, radius_);
    const double band = kBorderBandSigmas * scales[s];
    // One cell more than the band: the outermost held cell may reach in a fraction of a cell only.
    const auto band_cells = 1 + static_cast<std::uint32_t>(std::ceil(band / radius_));
    const std::vector<bool> one_sided = oneSidedBorderPoints(raster, planes_[s], members[s].points, band_cells,
                                                             scales[s], kOneSidedZ, kOneSidedSigmas * scales[s]);
    for (std::size_t j = 0; j < one_sided.size(); ++j) {
      if (one_sided[j]) {
        members[s].weights[j] = 0.0;
      } else if (raster.interior(j)) {
        members[s].weights[j] = 1.0;
      }
    }
    const Plane fitted = fitWeightedPlane(members[s].points, members[s].weights);
    if (fitted.valid) planes_[s] = fitted;
  }
  for (auto& list : segment_points_) list.clear();
  for (auto& list : segment_refs_) list.clear();
  for (std::size_t i = 0; i < pool.size(); ++i) {
    if (owner[i] < 0 || !(weights[i] > 0.0)) {
      membership_.release(pool[i].ref);
      continue;
    }
    const auto s = static_cast<std::uint32_t>(owner[i]);
    membership_.assign(pool[i].ref, s);
    segment_points_[s].push_back(pool[i].position);
    segment_refs_[s].push_back(pool[i].ref);
  }
}

}  // namespace plumb::reco::detail
