#include "engine/lod/framing.h"

#include <algorithm>
#include <cmath>

#include "engine/lod/octree.h"

namespace plumb::lod {
namespace {

// Enough points for the quantiles to mean something (100 beyond each end), few enough to read
// in a fraction of a second from a COPC file.
constexpr std::uint64_t kSamplePoints = 100'000;

}  // namespace

AxisHistograms::AxisHistograms(const Box3& bounds) : bounds_(bounds) {
  for (std::size_t a = 0; a < 3; ++a) {
    const double extent = bounds.max[a] - bounds.min[a];
    bins_per_metre_[a] = extent > 0.0 ? static_cast<double>(kFramingBins) / extent : 0.0;
    bins_[a].assign(kFramingBins, 0);
  }
}

void AxisHistograms::add(const std::array<double, 3>& point) {
  for (std::size_t a = 0; a < 3; ++a) {
    const double bin = std::floor((point[a] - bounds_.min[a]) * bins_per_metre_[a]);
    ++bins_[a][static_cast<std::size_t>(std::clamp(bin, 0.0, static_cast<double>(kFramingBins - 1)))];
  }
  ++count_;
}

void AxisHistograms::merge(const AxisHistograms& other) {
  for (std::size_t a = 0; a < 3; ++a) {
    for (std::size_t b = 0; b < kFramingBins; ++b) bins_[a][b] += other.bins_[a][b];
  }
  count_ += other.count_;
}

void AxisHistograms::clear() {
  for (auto& bins : bins_) std::fill(bins.begin(), bins.end(), 0);
  count_ = 0;
}

Box3 AxisHistograms::framingBox() const {
  Box3 box = bounds_;
  if (count_ == 0) return box;
  // At most this many points may lie beyond each end.
  const auto beyond = static_cast<std::uint64_t>(kFramingQuantile * static_cast<double>(count_));
  for (std::size_t a = 0; a < 3; ++a) {
    if (bins_per_metre_[a] == 0.0) continue;
    const std::vector<std::uint64_t>& bins = bins_[a];
    std::size_t low = 0;
    for (std::uint64_t below = bins[0]; below <= beyond && low + 1 < kFramingBins;) below += bins[++low];
    std::size_t high = kFramingBins - 1;
    for (std::uint64_t above = bins[high]; above <= beyond && high > low;) above += bins[--high];
    const double width = 1.0 / bins_per_metre_[a];
    box.min[a] = std::max(bounds_.min[a], bounds_.min[a] + static_cast<double>(low) * width);
    box.max[a] = std::min(bounds_.max[a], bounds_.min[a] + static_cast<double>(high + 1) * width);
  }
  return box;
}

Box3 framingBox(const Octree& octree) {
  const OctreeHeader& header = octree.header();
  if (header.framing) return *header.framing;
  AxisHistograms histograms(header.bounds);
  // Nodes come sorted by level: read whole levels, so that the sample covers the whole cloud.
  std::uint32_t level = 0;
  for (const NodeInfo& node : octree.nodes()) {
    if (node.key.level != level) {
      if (histograms.count() >= kSamplePoints) break;
      level = node.key.level;
    }
    const NodePoints points = octree.load(node);
    for (std::size_t i = 0; i < points.size(); ++i) histograms.add(points.position(i));
  }
  return histograms.framingBox();
}

}  // namespace plumb::lod
