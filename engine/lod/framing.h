#pragma once
// The box that frames a cloud in a view: its bulk, without the stray points every scan has (a
// return off a bird, a multipath reflection, a point through a window far across the street).
// Framed on its bounds, two returns 17 m above a 9 m interior scan make the building a tenth of
// the picture; the standard views (`plumb render --view`, the viewer's Home and view buttons)
// frame this box instead.
//
// Per axis, the box runs from the kFramingQuantile-th to the (1 - kFramingQuantile)-th quantile
// of the points' coordinates, read off a histogram of kFramingBins bins over the bounds and
// rounded outwards to whole bins. A cloud of fewer than 1 / kFramingQuantile points, or without
// strays, is framed on its bounds.

#include <array>
#include <cstdint>
#include <vector>

#include "engine/lod/cube.h"

namespace plumb::lod {

class Octree;

constexpr double kFramingQuantile = 0.001;
constexpr std::size_t kFramingBins = 4096;

// Histograms of the points' x, y and z over a box: built in parts (one per batch of points, in
// parallel) and merged.
class AxisHistograms {
 public:
  explicit AxisHistograms(const Box3& bounds);

  void add(const std::array<double, 3>& point);
  void merge(const AxisHistograms& other);
  void clear();
  std::uint64_t count() const { return count_; }
  const Box3& bounds() const { return bounds_; }

  // The framing box of the points added (the bounds when none were).
  Box3 framingBox() const;

 private:
  Box3 bounds_;
  std::array<double, 3> bins_per_metre_{};
  std::array<std::vector<std::uint64_t>, 3> bins_;
  std::uint64_t count_ = 0;
};

// The box to frame `octree` by: its header's (octree format 3, measured on every point by
// `plumb import`) or, for older octrees and COPC files, measured on the shallowest levels (whole
// levels until about 100,000 points are read; they thin the cloud evenly, so a stray point
// counts for as much of the sample as it holds of the space). Loads those nodes, so it may throw
// what Octree::load throws.
Box3 framingBox(const Octree& octree);

}  // namespace plumb::lod
