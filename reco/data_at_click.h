#pragma once
// What the cloud holds where the user clicks, for the detail that follows the data
// (parametersForView): how far apart the points lie there, measured on the points themselves at
// full detail, not on the octree's levels (a level's spacing is where its grid subsamples the
// cloud; the deepest level's follows the leaves' capacity, not the scan: 0.9 mm on a 1 M-point
// room whose walls hold a point per centimetre).

#include <Eigen/Core>

#include "reco/parameters.h"

namespace plumb::lod {
class NodeCache;
}

namespace plumb::reco {

// The cloud's point nearest to `click` (the point the user sees there), and around it the areal
// spacing sqrt(pi rho^2 / k) of its k = kDataAtClickNeighbours nearest points, rho the k-th
// distance: what a point per spacing on a surface through it gives. Where the point lies on an
// edge or a corner, the surfaces meeting there count together and the spacing comes out finer
// (up to sqrt(3)): the detail errs to the fine side. Noise thicker than rho thins the points a
// ball holds and makes it coarser. spacing_m is 0 where fewer than k points lie within 2.56 m of
// the click (an isolated point: nothing to measure). Cost: the octree nodes within a few
// spacings of the click, at every level; they load through `cache`.
DataAtClick dataAtClick(lod::NodeCache& cache, const Eigen::Vector3d& click);

inline constexpr std::size_t kDataAtClickNeighbours = 64;

}  // namespace plumb::reco
