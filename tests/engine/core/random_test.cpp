#include "engine/core/random.h"

#include <gtest/gtest.h>

#include <cmath>

namespace plumb {
namespace {

TEST(Random, SameSeedSameSequenceOtherSeedOtherSequence) {
  Random a(42), b(42), c(43);
  bool differs = false;
  for (int i = 0; i < 1000; ++i) {
    const std::uint64_t x = a.next();
    EXPECT_EQ(x, b.next());
    differs |= x != c.next();
  }
  EXPECT_TRUE(differs);
}

TEST(Random, UniformAndGaussianHaveTheirMoments) {
  Random random(7);
  constexpr int kSamples = 200'000;
  double sum_u = 0, sum_g = 0, sum_g2 = 0;
  for (int i = 0; i < kSamples; ++i) {
    const double u = random.uniform();
    ASSERT_GE(u, 0.0);
    ASSERT_LT(u, 1.0);
    sum_u += u;
    const double g = random.gaussian();
    ASSERT_TRUE(std::isfinite(g));
    sum_g += g;
    sum_g2 += g * g;
  }
  EXPECT_NEAR(sum_u / kSamples, 0.5, 0.005);
  EXPECT_NEAR(sum_g / kSamples, 0.0, 0.01);
  EXPECT_NEAR(std::sqrt(sum_g2 / kSamples), 1.0, 0.01);
}

TEST(Random, BelowStaysInRangeAndCoversIt) {
  Random random(9);
  int seen[7] = {};
  for (int i = 0; i < 7000; ++i) {
    const std::uint64_t value = random.below(7);
    ASSERT_LT(value, 7u);
    ++seen[value];
  }
  for (int count : seen) EXPECT_GT(count, 800);
}

TEST(Random, MixSeedSeparatesBlocks) {
  EXPECT_NE(mixSeed(1, 0), mixSeed(1, 1));
  EXPECT_NE(mixSeed(1, 5), mixSeed(2, 5));
  EXPECT_EQ(mixSeed(3, 4, 5), mixSeed(3, 4, 5));
}

}  // namespace
}  // namespace plumb
