// The continuity test's inner loop against a point-by-point reference with a branch per test.

#include "reco/continuity_scan.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <vector>

#include "engine/core/random.h"
#include "reco/point_grid.h"

namespace plumb::reco {
namespace {

struct Reference {
  std::vector<std::uint32_t> free_around;
  ContinuitySums sums;
};

Reference scanPointByPoint(const ContinuityScan& scan, const GridIndex::Bucket& bucket,
                           std::span<const std::uint8_t> owners) {
  Reference reference;
  for (std::size_t k = 0; k < bucket.indices.size(); ++k) {
    const std::uint8_t owner = owners[k];
    if (owner != 0 && owner != scan.own) continue;
    const float dx = bucket.x[k] - scan.at[0];
    const float dy = bucket.y[k] - scan.at[1];
    const float dz = bucket.z[k] - scan.at[2];
    if (dx * dx + dy * dy + dz * dz > scan.radius2) continue;
    ++reference.sums.near;
    if (owner == 0) reference.free_around.push_back(bucket.indices[k]);
    const float d =
        scan.normal[0] * bucket.x[k] + scan.normal[1] * bucket.y[k] + scan.normal[2] * bucket.z[k] + scan.origin_offset;
    if (std::abs(d) >= scan.window) continue;
    const auto units = static_cast<std::int64_t>(d * scan.units_per_m);
    if (owner == 0) {
      reference.sums.free_sum += units;
      ++reference.sums.free_count;
    } else {
      reference.sums.own_sum += units;
      ++reference.sums.own_count;
    }
  }
  return reference;
}

// A noisy tilted plane with points of three owners (free, the segment's, another segment's),
// bucketed by a grid coarse enough that some buckets span several of the scan's 64-point chunks:
// the same list, counts and sums as the reference, for candidates all over the plane.
TEST(ContinuityScan, FindsWhatAPointByPointScanFinds) {
  Random random(11);
  const Eigen::Vector3d origin(512000.0, 5403000.0, 250.0);
  const Eigen::Vector3d normal = Eigen::Vector3d(0.2, -0.3, 1.0).normalized();
  std::vector<Eigen::Vector3d> points;
  std::vector<std::uint8_t> owner_of;
  for (int i = 0; i < 20000; ++i) {
    const double x = random.uniform() - 0.5;
    const double y = random.uniform() - 0.5;
    const double z = -(normal.x() * x + normal.y() * y) / normal.z() + 0.01 * random.gaussian();
    points.push_back(origin + Eigen::Vector3d(x, y, z));
    const double which = random.uniform();
    owner_of.push_back(which < 0.5 ? 0 : which < 0.9 ? 3 : 1);
  }
  const double radius = 0.15;
  const PointGrid grid(origin, radius);
  const GridIndex index(grid, points);
  std::vector<std::uint8_t> owners_by_grid;
  for (std::uint32_t i : index.order()) owners_by_grid.push_back(owner_of[i]);

  std::size_t compared = 0;
  std::size_t long_buckets = 0;
  for (int c = 0; c < 200; ++c) {
    const Eigen::Vector3d& p = points[static_cast<std::size_t>(random.uniform() * 19999.0)];
    ContinuityScan scan;
    const Eigen::Vector3f at = (p - origin).cast<float>();
    scan.at = {at.x(), at.y(), at.z()};
    scan.normal = {static_cast<float>(normal.x()), static_cast<float>(normal.y()), static_cast<float>(normal.z())};
    scan.origin_offset = 0.0f;
    scan.window = 0.02f;
    scan.radius2 = static_cast<float>(radius * radius);
    scan.own = 3;
    scan.units_per_m = continuityUnitsPerMetre(scan.window);
    grid.forEachAroundWithin(p, radius, [&](const GridKey& key) {
      const GridIndex::Bucket bucket = index.bucket(key);
      if (bucket.indices.empty()) return;
      const std::span<const std::uint8_t> owners(owners_by_grid.data() + bucket.first, bucket.indices.size());
      std::vector<std::uint32_t> listed{7};  // appended to, not replaced
      ContinuitySums sums;
      sums.free_sum = 5;  // added to, not replaced
      scanBucket(scan, bucket, owners, listed, sums);
      const Reference reference = scanPointByPoint(scan, bucket, owners);
      ASSERT_EQ(listed.front(), 7u);
      EXPECT_EQ(std::vector<std::uint32_t>(listed.begin() + 1, listed.end()), reference.free_around);
      EXPECT_EQ(sums.free_sum, reference.sums.free_sum + 5);
      EXPECT_EQ(sums.own_sum, reference.sums.own_sum);
      EXPECT_EQ(sums.free_count, reference.sums.free_count);
      EXPECT_EQ(sums.own_count, reference.sums.own_count);
      EXPECT_EQ(sums.near, reference.sums.near);
      ++compared;
      if (bucket.indices.size() > 64) ++long_buckets;
    });
  }
  EXPECT_GT(compared, 1000u);
  EXPECT_GT(long_buckets, 100u);
}

// Micrometres, except where a window so wide that 64 offsets within it would overflow a 32-bit sum.
TEST(ContinuityScan, UnitsAreMicrometresWhereTheSumsFit) {
  EXPECT_EQ(continuityUnitsPerMetre(0.03), 1e6f);
  EXPECT_EQ(continuityUnitsPerMetre(16.0), 1e6f);
  const double window = 100.0;
  const double units = continuityUnitsPerMetre(window);
  EXPECT_LT(units, 1e6);
  EXPECT_LE(64.0 * window * units, std::pow(2.0, 30.0) * 1.0001);
}

}  // namespace
}  // namespace plumb::reco
