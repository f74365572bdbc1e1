#pragma once
// The inner loop of the grower's continuity test (Grower::continuesSurface): over the points of
// one grid cell, which of them are free or the segment's and within the search radius, and the
// sums of their offsets from the segment's plane within the window.
//
// Offsets are summed in integer units (micrometres, coarser only where a window of more than
// 16 m would overflow a chunk's 32-bit sums): integer sums are exact, so the order of the
// additions cannot change them, and the compiler runs the loop on several points at once in
// vector registers, without a branch. Whether a point is near, free and within the window is as good as random;
// the branches of a point-by-point loop mispredicted on half the points, most of the test's time.

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "reco/grid_index.h"

namespace plumb::reco {

// What the scan asks of each point, in single precision relative to the grid's origin.
struct ContinuityScan {
  std::array<float, 3> at{};      // the candidate point
  std::array<float, 3> normal{};  // the segment's plane: offset = normal . q + origin_offset
  float origin_offset = 0.0f;
  float window = 0.0f;   // offsets at or beyond it are not summed
  float radius2 = 0.0f;  // the squared search radius
  std::uint8_t own = 0;  // the segment's flag (s + 1); 0 is a free point
  float units_per_m = 0.0f;
};

struct ContinuitySums {
  std::int64_t free_sum = 0;  // in units (ContinuityScan::units_per_m)
  std::int64_t own_sum = 0;
  std::uint32_t free_count = 0;  // points summed
  std::uint32_t own_count = 0;
  std::uint32_t near = 0;  // free and own points within the radius, summed or not
};

// The units of a scan whose window is `window_m`: micrometres where a chunk's sums fit.
float continuityUnitsPerMetre(double window_m);

// Adds the bucket's points to `sums` and appends its free points within the radius, in the
// bucket's order, to `free_around`. `owners`: the points' flags, in the bucket's order.
void scanBucket(const ContinuityScan& scan, const GridIndex::Bucket& bucket, std::span<const std::uint8_t> owners,
                std::vector<std::uint32_t>& free_around, ContinuitySums& sums);

}  // namespace plumb::reco
