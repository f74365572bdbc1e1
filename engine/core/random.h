#pragma once
// A small, fast, seedable random generator for simulation and RANSAC: xoshiro256+ seeded
// through splitmix64 (Blackman and Vigna, "Scrambled linear pseudorandom number generators",
// 2021). Deterministic for a seed on every platform, unlike the std distributions.
//
// Not thread-safe: give each thread or each block of work its own generator, seeded from
// mixSeed(seed, block...) so results do not depend on scheduling.

#include <cmath>
#include <cstdint>
#include <numbers>

namespace plumb {

// splitmix64: a bijective 64-bit mixer, used to spread seeds.
constexpr std::uint64_t splitMix64(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

// A seed for block `a` (and `b`) of the work seeded by `seed`.
constexpr std::uint64_t mixSeed(std::uint64_t seed, std::uint64_t a, std::uint64_t b = 0) {
  return splitMix64(splitMix64(splitMix64(seed) ^ a) ^ b);
}

class Random {
 public:
  explicit Random(std::uint64_t seed) {
    std::uint64_t x = seed;
    for (auto& word : state_) {
      x = splitMix64(x);
      word = x;
    }
  }

  std::uint64_t next() {
    const std::uint64_t result = state_[0] + state_[3];
    const std::uint64_t t = state_[1] << 17;
    state_[2] ^= state_[0];
    state_[3] ^= state_[1];
    state_[1] ^= state_[2];
    state_[0] ^= state_[3];
    state_[2] ^= t;
    state_[3] = (state_[3] << 45) | (state_[3] >> 19);
    return result;
  }

  // Uniform in [0, 1), 53 bits.
  double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }

  // Uniform integer in [0, bound), bound > 0 (Lemire's multiply-shift; bias below 2^-32 for
  // bounds under 2^32).
  std::uint64_t below(std::uint64_t bound) {
    __extension__ using Wide = unsigned __int128;  // GCC and Clang; __extension__ silences -Wpedantic
    return static_cast<std::uint64_t>((static_cast<Wide>(next()) * bound) >> 64);
  }

  // Standard normal (Box-Muller; the second value of each pair is kept for the next call).
  double gaussian() {
    if (has_spare_) {
      has_spare_ = false;
      return spare_;
    }
    const double u = 1.0 - uniform();  // (0, 1]: log stays finite
    const double radius = std::sqrt(-2.0 * std::log(u));
    const double angle = 2.0 * std::numbers::pi * uniform();
    spare_ = radius * std::sin(angle);
    has_spare_ = true;
    return radius * std::cos(angle);
  }

 private:
  std::uint64_t state_[4];
  double spare_ = 0.0;
  bool has_spare_ = false;
};

}  // namespace plumb
