#pragma once
// Nearest-hit ray casting against a Scene's rectangles through a bounding volume hierarchy.
// Built once, then immutable: intersect() may be called from any number of threads at once.

#include <cstdint>
#include <vector>

#include "reco/sim/scene.h"

namespace plumb::reco::sim {

struct RayHit {
  double distance;     // along the unit direction, metres
  std::uint32_t quad;  // index into Scene::quads
};

class RayCaster {
 public:
  // Keeps a reference to `scene`, which must outlive the caster and stay unchanged.
  explicit RayCaster(const Scene& scene);

  // The nearest rectangle hit by origin + t * direction for 0 < t < max_distance, if any.
  // `direction` must be a unit vector (scene-local frame).
  bool intersect(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction, double max_distance,
                 RayHit& hit) const;

 private:
  struct Node {
    double lo[3];
    double hi[3];
    std::uint32_t first;  // leaf: first entry of quad_order_; inner: index of the right child
    std::uint32_t count;  // leaf: number of rectangles; inner: 0 (left child = this index + 1)
  };
  std::uint32_t build(std::uint32_t first, std::uint32_t count);
  bool hitsQuad(const Quad& quad, const double origin[3], const double direction[3], double t_max, double& t) const;

  const Scene& scene_;
  std::vector<Node> nodes_;
  std::vector<std::uint32_t> quad_order_;
};

}  // namespace plumb::reco::sim
