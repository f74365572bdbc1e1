// Edge and corner reconstruction, paper section 4.1.
//
//   1. For every pair of segments whose valid planes meet at more than min_angle: intersect
//      them (in coordinates relative to the segments' centroids, exact at UTM scale).
//   2. Gather each segment's points near the line (within 2r, or 8 RMS of its plane where
//      wider: at full detail r may be about the noise); with at least min_near_points from
//      each, project them onto the line: the 5th to 95th percentile is the support range and
//      gives the edge's endpoints.
//   3. For every triple of segments whose pairs are all non-parallel, solve the three planes
//      for the corner; viable when each segment reaches it (a point near it: a corner of a
//      room is at the very end of its three walls, where each has only a quarter disc of
//      points). Its support is the three regression variances.

#include "reco/edges_and_corners.h"

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>

namespace plumb::reco {
namespace {

bool intersecting(const Plane& a, const Plane& b, double min_sine) {
  return a.normal.cross(b.normal).norm() > min_sine;
}

double percentile(std::vector<double>& values, double q) {
  const auto index = static_cast<std::size_t>(std::lround(q * static_cast<double>(values.size() - 1)));
  std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(index), values.end());
  return values[index];
}

// The line where planes a and b meet: a point near their centroids and a unit direction.
std::pair<Eigen::Vector3d, Eigen::Vector3d> intersectionLine(const Plane& a, const Plane& b) {
  const Eigen::Vector3d reference = 0.5 * (a.centroid + b.centroid);
  const Eigen::Vector3d direction = a.normal.cross(b.normal).normalized();
  Eigen::Matrix3d m;
  m.row(0) = a.normal.transpose();
  m.row(1) = b.normal.transpose();
  m.row(2) = direction.transpose();
  // n . (x - reference) = n . (centroid - reference) for both planes; no motion along the line.
  const Eigen::Vector3d rhs(a.normal.dot(a.centroid - reference), b.normal.dot(b.centroid - reference), 0.0);
  return {reference + m.partialPivLu().solve(rhs), direction};
}

}  // namespace

std::optional<std::pair<Eigen::Vector3d, Eigen::Vector3d>> lineOfPlanes(const Plane& a, const Plane& b,
                                                                        double min_angle_deg) {
  if (!intersecting(a, b, std::sin(min_angle_deg * M_PI / 180.0))) return std::nullopt;
  return intersectionLine(a, b);
}

std::optional<Eigen::Vector3d> cornerOfPlanes(const Plane& a, const Plane& b, const Plane& c, double min_angle_deg) {
  const double min_sine = std::sin(min_angle_deg * M_PI / 180.0);
  if (!intersecting(a, b, min_sine) || !intersecting(a, c, min_sine) || !intersecting(b, c, min_sine)) {
    return std::nullopt;
  }
  // Three planes through a common line (a pencil) have no single corner.
  if (std::abs(a.normal.cross(b.normal).normalized().dot(c.normal)) < min_sine) return std::nullopt;
  const Eigen::Vector3d reference = (a.centroid + b.centroid + c.centroid) / 3.0;
  Eigen::Matrix3d m;
  m.row(0) = a.normal.transpose();
  m.row(1) = b.normal.transpose();
  m.row(2) = c.normal.transpose();
  const Eigen::Vector3d rhs(a.normal.dot(a.centroid - reference), b.normal.dot(b.centroid - reference),
                            c.normal.dot(c.centroid - reference));
  return reference + m.partialPivLu().solve(rhs);
}

Features findEdgesAndCorners(std::span<const SegmentGeometry> segments, const FeatureOptions& options) {
  Features features;
  const double min_sine = std::sin(options.min_angle_deg * M_PI / 180.0);
  // Near a line or a corner: within 2r, or within noise_near_sigmas times the plane's RMS where
  // that is wider. Along an edge the growth turns away a strip of points about two inlier
  // windows wide (each 2.25 RMS), where the free points of the other surface pull the continuity
  // test's mean. At full detail on a dense scan r is a few point spacings, less than that strip
  // (a 100 M-point room at 5 mm noise: r 5.6 mm), and no segment kept a point within 2r of the
  // corner: the click at the corner found none.
  const auto nearOf = [&](std::uint32_t s) {
    return std::max(2.0 * options.search_radius, options.noise_near_sigmas * segments[s].plane.rms);
  };
  const auto n = static_cast<std::uint32_t>(segments.size());
  auto usable = [&](std::uint32_t s) { return segments[s].plane.valid && !segments[s].points.empty(); };

  for (std::uint32_t i = 0; i < n; ++i) {
    for (std::uint32_t j = i + 1; j < n; ++j) {
      if (!usable(i) || !usable(j) || !intersecting(segments[i].plane, segments[j].plane, min_sine)) continue;
      const auto [origin, direction] = intersectionLine(segments[i].plane, segments[j].plane);
      std::vector<double> along;
      bool both_near = true;
      for (std::uint32_t s : {i, j}) {
        const double near = nearOf(s);
        std::uint32_t count = 0;
        for (const Eigen::Vector3d& p : segments[s].points) {
          const Eigen::Vector3d offset = p - origin;
          const double t = offset.dot(direction);
          if ((offset - t * direction).squaredNorm() <= near * near) {
            along.push_back(t);
            ++count;
          }
        }
        both_near = both_near && count >= options.min_near_points;
      }
      if (!both_near) continue;
      const auto support = static_cast<std::uint32_t>(along.size());
      const double low = percentile(along, options.low_percentile);
      const double high = percentile(along, options.high_percentile);
      features.edges.push_back({{i, j}, origin + low * direction, origin + high * direction, direction, support});
    }
  }

  for (std::uint32_t i = 0; i < n; ++i) {
    for (std::uint32_t j = i + 1; j < n; ++j) {
      for (std::uint32_t k = j + 1; k < n; ++k) {
        if (!usable(i) || !usable(j) || !usable(k)) continue;
        const std::optional<Eigen::Vector3d> found =
            cornerOfPlanes(segments[i].plane, segments[j].plane, segments[k].plane, options.min_angle_deg);
        if (!found) continue;
        const Eigen::Vector3d& corner = *found;
        // Each segment must reach the corner: a point of it (a vertex of its outline) within its near distance
        // (nearOf).
        const std::array<std::uint32_t, 3> trio{i, j, k};
        const bool all_near = std::all_of(trio.begin(), trio.end(), [&](std::uint32_t s) {
          const double near = nearOf(s);
          return std::any_of(segments[s].points.begin(), segments[s].points.end(),
                             [&](const Eigen::Vector3d& p) { return (p - corner).squaredNorm() <= near * near; });
        });
        if (!all_near) continue;
        features.corners.push_back(
            {{i, j, k}, corner, {segments[i].plane.lambda2, segments[j].plane.lambda2, segments[k].plane.lambda2}});
      }
    }
  }
  return features;
}

}  // namespace plumb::reco
