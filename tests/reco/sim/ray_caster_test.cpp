#include "reco/sim/ray_caster.h"

#include <gtest/gtest.h>

#include <limits>

#include "engine/core/random.h"
#include "reco/sim/scene_builder.h"
#include "reco/sim/scenes.h"

namespace plumb::reco::sim {
namespace {

// Every rectangle tried in turn: the oracle for the hierarchy.
bool bruteForce(const Scene& scene, const Eigen::Vector3d& o, const Eigen::Vector3d& d, double max, RayHit& best) {
  bool found = false;
  best.distance = max;
  for (std::uint32_t i = 0; i < scene.quads.size(); ++i) {
    const Quad& q = scene.quads[i];
    if (d[q.axis] == 0.0) continue;
    const double t = (q.coord - o[q.axis]) / d[q.axis];
    if (!(t > 1e-9 && t < best.distance)) continue;
    const Eigen::Vector3d p = o + t * d;
    const double u = p[(q.axis + 1) % 3], v = p[(q.axis + 2) % 3];
    if (!q.extent.contains(u, v)) continue;
    bool in_hole = false;
    for (std::uint32_t h = q.first_hole; h < q.first_hole + q.hole_count; ++h) {
      const Rect2& r = scene.holes[h];
      in_hole |= u > r.u0 && u < r.u1 && v > r.v0 && v < r.v1;
    }
    if (in_hole) continue;
    best = {t, i};
    found = true;
  }
  return found;
}

//   y
//   4 +-----------+        a 6 x 4 x 3 m room; the x+ wall has a 1 m hole
//     |     o ->  [ hole   at y in [1.5, 2.5], z in [1, 2]
//   0 +-----------+
//     0           6  x
TEST(RayCaster, HitsTheNearestWallAndPassesThroughHoles) {
  SceneBuilder b("box");
  const MaterialId m = b.material("white", {255, 255, 255}, 1.0);
  const BoxFaces room = b.interior({{0, 0, 0}, {6, 4, 3}}, "room", m, m, m);
  b.cutHole(room.x_max, {{{6, 6}, {1.5, 2.5}, {1, 2}}});
  const Scene scene = std::move(b).build();
  const RayCaster caster(scene);

  RayHit hit;
  ASSERT_TRUE(caster.intersect({2, 1, 1.5}, {1, 0, 0}, 100, hit));
  EXPECT_NEAR(hit.distance, 4.0, 1e-12);
  EXPECT_EQ(scene.quads[hit.quad].plane, room.x_max);

  EXPECT_FALSE(caster.intersect({2, 2, 1.5}, {1, 0, 0}, 100, hit)) << "through the hole";
  ASSERT_TRUE(caster.intersect({2, 2, 1.5}, {0, 0, -1}, 100, hit));
  EXPECT_EQ(scene.quads[hit.quad].plane, room.z_min);
  EXPECT_NEAR(hit.distance, 1.5, 1e-12);
  EXPECT_FALSE(caster.intersect({2, 1, 1.5}, {1, 0, 0}, 3.9, hit)) << "beyond the maximum distance";
}

TEST(RayCaster, AgreesWithBruteForceOnEveryScene) {
  for (const std::string& name : sceneNames()) {
    const Scene scene = makeScene(name);
    const RayCaster caster(scene);
    Random random(11);
    int hits = 0;
    for (const Eigen::Vector3d& station : scene.stations) {
      for (int i = 0; i < 20'000; ++i) {
        Eigen::Vector3d d(random.gaussian(), random.gaussian(), random.gaussian());
        d.normalize();
        RayHit fast{}, slow{};
        const bool found_fast = caster.intersect(station, d, 80, fast);
        const bool found_slow = bruteForce(scene, station, d, 80, slow);
        ASSERT_EQ(found_fast, found_slow) << name << " ray " << i;
        if (found_fast) {
          ++hits;
          ASSERT_NEAR(fast.distance, slow.distance, 1e-12) << name;
        }
      }
    }
    EXPECT_GT(hits, 0) << name;
  }
}

}  // namespace
}  // namespace plumb::reco::sim
