#pragma once
// How far apart the points of a scan are, as the region grower needs to know it (paper section
// 3.7: r is twice the mean point spacing). Two measures, because scans are not uniform:
//   - the median distance from a point to its nearest neighbour, which sees the spacing along
//     the scanner's lines;
//   - the areal spacing of a planar patch, sqrt(area / points), which also sees the gaps between
//     the lines: on a floor seen at a grazing angle the lines lie several times farther apart
//     than the points along them, and a radius from the first measure cannot cross them.

#include <Eigen/Core>
#include <span>

#include "reco/plane.h"

namespace plumb::reco {

// The median distance from a point to its nearest other point, over a sample of at most 512 of
// `points`, looked for as far as `reach` (farther neighbours count as `reach`). Duplicates
// (distance 0) are no neighbours. 0 for fewer than two points.
double medianNearestDistance(std::span<const Eigen::Vector3d> points, double reach);

// sqrt(area / count) of the points projected onto `plane`, the area being that of their convex
// hull. 0 for fewer than three points or a degenerate hull (collinear points).
double arealSpacing(const Plane& plane, std::span<const Eigen::Vector3d> points);

}  // namespace plumb::reco
