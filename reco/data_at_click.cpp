// The data's spacing at a click (data_at_click.h). The points of every octree node within a
// radius of the click, first 1 cm; the nearest to the click; its k nearest among them. The
// radius grows four-fold until it holds the k-th neighbour of that point whole (the nearest
// point plus the k-th distance inside the radius), at most 2.56 m.

#include "reco/data_at_click.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "engine/lod/lod_query.h"
#include "engine/lod/node_cache.h"

namespace plumb::reco {
namespace {

constexpr double kFirstRadius = 0.01;
constexpr double kLastRadius = 2.56;

}  // namespace

DataAtClick dataAtClick(lod::NodeCache& cache, const Eigen::Vector3d& click) {
  const lod::Octree& octree = cache.octree();
  const std::uint32_t depth = octree.header().depth;
  DataAtClick data;
  data.full_density = std::pow(octree.spacing(depth), -3.0);
  const std::array<double, 3> centre{click.x(), click.y(), click.z()};
  std::vector<Eigen::Vector3d> points;
  std::vector<double> distances2;
  for (double radius = kFirstRadius; radius <= kLastRadius * 1.001; radius *= 4.0) {
    points.clear();
    for (const lod::NodeInfo* node : lod::nodesInSphere(octree, centre, radius, depth)) {
      const auto node_points = cache.get(node->key);
      for (std::size_t i = 0; i < node_points->size(); ++i) {
        const std::array<double, 3> p = node_points->position(i);
        const Eigen::Vector3d point(p[0], p[1], p[2]);
        if ((point - click).squaredNorm() <= radius * radius) points.push_back(point);
      }
    }
    if (points.size() < kDataAtClickNeighbours) continue;
    const Eigen::Vector3d nearest = *std::min_element(points.begin(), points.end(), [&](const auto& a, const auto& b) {
      return (a - click).squaredNorm() < (b - click).squaredNorm();
    });
    distances2.clear();
    for (const Eigen::Vector3d& p : points) distances2.push_back((p - nearest).squaredNorm());
    const auto kth = distances2.begin() + static_cast<std::ptrdiff_t>(kDataAtClickNeighbours - 1);
    std::nth_element(distances2.begin(), kth, distances2.end());
    const double rho = std::sqrt(*kth);
    // Points beyond the radius might be nearer to `nearest` than the k-th found: look farther.
    if ((nearest - click).norm() + rho > radius) continue;
    data.spacing_m = rho * std::sqrt(M_PI / static_cast<double>(kDataAtClickNeighbours));
    return data;
  }
  return data;
}

}  // namespace plumb::reco
