#include "reco/sim/ray_caster.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>

namespace plumb::reco::sim {
namespace {

constexpr std::uint32_t kLeafSize = 2;
constexpr int kMaxDepth = 64;
// Rectangles are flat: their boxes get this thickness so the slab test never divides 0 by 0.
constexpr double kBoxPadding = 1e-7;
// Hits closer than this are the ray's own origin surface.
constexpr double kMinDistance = 1e-9;

void quadBounds(const Quad& q, double lo[3], double hi[3]) {
  const int u = (q.axis + 1) % 3, v = (q.axis + 2) % 3;
  lo[q.axis] = q.coord - kBoxPadding;
  hi[q.axis] = q.coord + kBoxPadding;
  lo[u] = q.extent.u0 - kBoxPadding;
  hi[u] = q.extent.u1 + kBoxPadding;
  lo[v] = q.extent.v0 - kBoxPadding;
  hi[v] = q.extent.v1 + kBoxPadding;
}

}  // namespace

RayCaster::RayCaster(const Scene& scene) : scene_(scene) {
  quad_order_.resize(scene.quads.size());
  for (std::uint32_t i = 0; i < quad_order_.size(); ++i) quad_order_[i] = i;
  nodes_.reserve(2 * scene.quads.size() + 1);
  if (!scene.quads.empty()) build(0, static_cast<std::uint32_t>(scene.quads.size()));
}

// Median split on the longest axis of the rectangle centres, depth first: an inner node's left
// child directly follows it, so the node stores only its right child.
std::uint32_t RayCaster::build(std::uint32_t first, std::uint32_t count) {
  const auto index = static_cast<std::uint32_t>(nodes_.size());
  nodes_.push_back({});
  Node node{};
  std::fill(std::begin(node.lo), std::end(node.lo), std::numeric_limits<double>::infinity());
  std::fill(std::begin(node.hi), std::end(node.hi), -std::numeric_limits<double>::infinity());
  double centre_lo[3] = {node.lo[0], node.lo[1], node.lo[2]};
  double centre_hi[3] = {node.hi[0], node.hi[1], node.hi[2]};
  for (std::uint32_t i = first; i < first + count; ++i) {
    double lo[3], hi[3];
    quadBounds(scene_.quads[quad_order_[i]], lo, hi);
    for (int a = 0; a < 3; ++a) {
      node.lo[a] = std::min(node.lo[a], lo[a]);
      node.hi[a] = std::max(node.hi[a], hi[a]);
      const double centre = 0.5 * (lo[a] + hi[a]);
      centre_lo[a] = std::min(centre_lo[a], centre);
      centre_hi[a] = std::max(centre_hi[a], centre);
    }
  }
  if (count <= kLeafSize) {
    node.first = first;
    node.count = count;
    nodes_[index] = node;
    return index;
  }
  int axis = 0;
  for (int a = 1; a < 3; ++a) {
    if (centre_hi[a] - centre_lo[a] > centre_hi[axis] - centre_lo[axis]) axis = a;
  }
  const auto begin = quad_order_.begin() + first;
  const auto middle = begin + count / 2;
  std::nth_element(begin, middle, begin + count, [&](std::uint32_t a, std::uint32_t b) {
    double lo_a[3], hi_a[3], lo_b[3], hi_b[3];
    quadBounds(scene_.quads[a], lo_a, hi_a);
    quadBounds(scene_.quads[b], lo_b, hi_b);
    return lo_a[axis] + hi_a[axis] < lo_b[axis] + hi_b[axis];
  });
  node.count = 0;
  nodes_[index] = node;
  build(first, count / 2);  // the left child lands at index + 1
  nodes_[index].first = build(first + count / 2, count - count / 2);
  return index;
}

bool RayCaster::hitsQuad(const Quad& q, const double origin[3], const double direction[3], double t_max,
                         double& t) const {
  const double d = direction[q.axis];
  if (d == 0.0) return false;
  t = (q.coord - origin[q.axis]) / d;
  if (!(t > kMinDistance && t < t_max)) return false;
  const int u = (q.axis + 1) % 3, v = (q.axis + 2) % 3;
  const double pu = origin[u] + t * direction[u];
  const double pv = origin[v] + t * direction[v];
  if (!q.extent.contains(pu, pv)) return false;
  for (std::uint32_t h = q.first_hole; h < q.first_hole + q.hole_count; ++h) {
    const Rect2& hole = scene_.holes[h];
    // Holes are open on their border so that a hole's edge belongs to the surrounding surface.
    if (pu > hole.u0 && pu < hole.u1 && pv > hole.v0 && pv < hole.v1) return false;
  }
  return true;
}

bool RayCaster::intersect(const Eigen::Vector3d& origin_vector, const Eigen::Vector3d& direction_vector,
                          double max_distance, RayHit& hit) const {
  if (nodes_.empty()) return false;
  const double origin[3] = {origin_vector.x(), origin_vector.y(), origin_vector.z()};
  const double direction[3] = {direction_vector.x(), direction_vector.y(), direction_vector.z()};
  double inverse[3];
  for (int a = 0; a < 3; ++a) {
    // A huge finite value instead of infinity keeps (bound - origin) * inverse free of NaN.
    inverse[a] = std::abs(direction[a]) > 1e-300 ? 1.0 / direction[a] : std::copysign(1e300, direction[a]);
  }

  double best = max_distance;
  bool found = false;
  std::uint32_t stack[kMaxDepth];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const std::uint32_t current = stack[--top];
    const Node& node = nodes_[current];
    double t_enter = 0.0, t_exit = best;
    for (int a = 0; a < 3; ++a) {
      double t0 = (node.lo[a] - origin[a]) * inverse[a];
      double t1 = (node.hi[a] - origin[a]) * inverse[a];
      if (t0 > t1) std::swap(t0, t1);
      t_enter = std::max(t_enter, t0);
      t_exit = std::min(t_exit, t1);
    }
    if (t_enter > t_exit) continue;
    if (node.count > 0) {
      for (std::uint32_t i = node.first; i < node.first + node.count; ++i) {
        double t;
        if (hitsQuad(scene_.quads[quad_order_[i]], origin, direction, best, t)) {
          best = t;
          hit = {t, quad_order_[i]};
          found = true;
        }
      }
    } else {
      assert(top + 2 <= kMaxDepth && "BVH deeper than the traversal stack");
      stack[top++] = node.first;   // right child
      stack[top++] = current + 1;  // left child, visited first
    }
  }
  return found;
}

}  // namespace plumb::reco::sim
