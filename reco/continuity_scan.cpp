#include "reco/continuity_scan.h"

#include <algorithm>
#include <cmath>

namespace plumb::reco {

namespace {

// Points per chunk of 32-bit sums.
constexpr std::size_t kChunk = 64;

}  // namespace

float continuityUnitsPerMetre(double window_m) {
  // Each summed offset is below window_m in magnitude: a chunk's sum stays below 2^30.
  constexpr double kMicrometresPerMetre = 1e6;
  const double fitting = static_cast<double>(1u << 30) / (window_m * static_cast<double>(kChunk));
  return static_cast<float>(std::min(kMicrometresPerMetre, fitting));
}

void scanBucket(const ContinuityScan& scan, const GridIndex::Bucket& bucket, std::span<const std::uint8_t> owners,
                std::vector<std::uint32_t>& free_around, ContinuitySums& sums) {
  const std::size_t n = bucket.indices.size();
  const std::size_t listed = free_around.size();
  free_around.resize(listed + n);
  std::uint32_t* const out = free_around.data() + listed;
  std::size_t free_listed = 0;
  // Locals, so that the compiler keeps them in registers (a store to the list might alias them).
  const float ax = scan.at[0], ay = scan.at[1], az = scan.at[2];
  const float nx = scan.normal[0], ny = scan.normal[1], nz = scan.normal[2];
  const float offset = scan.origin_offset, window = scan.window, radius2 = scan.radius2;
  const float units_per_m = scan.units_per_m;
  const std::uint8_t own = scan.own;
  for (std::size_t begin = 0; begin < n; begin += kChunk) {
    const std::size_t count = std::min(kChunk, n - begin);
    const float* x = bucket.x.data() + begin;
    const float* y = bucket.y.data() + begin;
    const float* z = bucket.z.data() + begin;
    const std::uint8_t* owner = owners.data() + begin;
    std::array<std::uint8_t, kChunk> listed_flags{};
    std::int32_t free_sum = 0;
    std::int32_t own_sum = 0;
    std::int32_t free_count = 0;
    std::int32_t own_count = 0;
    std::int32_t near_count = 0;
    for (std::size_t k = 0; k < count; ++k) {
      // Each test as an integer 0 or 1 and each choice as a mask: no branch for the compiler
      // to keep.
      const float dx = x[k] - ax;
      const float dy = y[k] - ay;
      const float dz = z[k] - az;
      const std::int32_t near = dx * dx + dy * dy + dz * dz <= radius2;
      const std::int32_t flag = owner[k];
      const std::int32_t is_free = near & static_cast<std::int32_t>(flag == 0);
      const std::int32_t is_own = near & static_cast<std::int32_t>(flag == own);
      const float d = nx * x[k] + ny * y[k] + nz * z[k] + offset;
      const std::int32_t in_window = std::abs(d) < window;
      // Only an offset within the window is converted: one beyond it may not fit an integer.
      const auto units = static_cast<std::int32_t>(d * static_cast<float>(in_window) * units_per_m);
      const std::int32_t free_summed = is_free & in_window;
      const std::int32_t own_summed = is_own & in_window;
      free_sum += units & -free_summed;
      free_count += free_summed;
      own_sum += units & -own_summed;
      own_count += own_summed;
      near_count += is_free | is_own;
      listed_flags[k] = static_cast<std::uint8_t>(is_free);
    }
    for (std::size_t k = 0; k < count; ++k) {
      out[free_listed] = bucket.indices[begin + k];
      free_listed += listed_flags[k];
    }
    sums.free_sum += free_sum;
    sums.own_sum += own_sum;
    sums.free_count += static_cast<std::uint32_t>(free_count);
    sums.own_count += static_cast<std::uint32_t>(own_count);
    sums.near += static_cast<std::uint32_t>(near_count);
  }
  free_around.resize(listed + free_listed);
}

}  // namespace plumb::reco
