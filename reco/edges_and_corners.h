#pragma once
// Edges and corners as intersections of segments (paper section 4.1): the maximum-likelihood
// features the drawing tools snap to.

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "reco/plane.h"

namespace plumb::reco {

// What the feature search needs of a segment: its plane and its points (world coordinates).
struct SegmentGeometry {
  Plane plane;
  std::span<const Eigen::Vector3d> points;
};

struct Edge {
  std::array<std::uint32_t, 2> segments;
  Eigen::Vector3d start;             // the support range: from the 5th ...
  Eigen::Vector3d end;               // ... to the 95th percentile of the nearby points along the line
  Eigen::Vector3d direction;         // unit, from start to end
  std::uint32_t support_points = 0;  // points near the line (FeatureOptions), both segments together
};

struct Corner {
  std::array<std::uint32_t, 3> segments;
  Eigen::Vector3d position;
  std::array<double, 3> support;  // the three regression variances lambda2, m^2 (smaller is stabler)
};

struct FeatureOptions {
  double search_radius = 0.05;     // r of the grow: points within 2r of a line or corner count as near
  double noise_near_sigmas = 8.0;  // or within this many times the segment's plane RMS, where wider
  double min_angle_deg = 10.0;     // planes closer to parallel than this do not intersect
  double low_percentile = 0.05;    // the support range along an edge
  double high_percentile = 0.95;
  std::uint32_t min_near_points = 5;  // per segment, to call it near an edge's line
};

struct Features {
  std::vector<Edge> edges;
  std::vector<Corner> corners;
};

// The point where three planes meet, or nothing when two of them are closer to parallel than
// `min_angle_deg` or all three pass through one line. Solved about the centroids' mean, so the
// result keeps its precision at UTM coordinates. No points are needed: a corner in a scan
// shadow is still where its planes meet.
std::optional<Eigen::Vector3d> cornerOfPlanes(const Plane& a, const Plane& b, const Plane& c,
                                              double min_angle_deg = 10.0);

// The line where two planes meet (a point on it near their centroids, and a unit direction), or
// nothing when they are closer to parallel than `min_angle_deg`.
std::optional<std::pair<Eigen::Vector3d, Eigen::Vector3d>> lineOfPlanes(const Plane& a, const Plane& b,
                                                                        double min_angle_deg = 10.0);

// All viable pairs (edges) and triples (corners) of segments: planes not parallel, each
// segment with points (a non-vanishing polygon), and each with points near the intersection.
Features findEdgesAndCorners(std::span<const SegmentGeometry> segments, const FeatureOptions& options = {});

}  // namespace plumb::reco
