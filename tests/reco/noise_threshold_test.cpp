// t_p from the data (reco/noise_threshold.h): the noise measures against known normal noise.

#include "reco/noise_threshold.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "engine/core/random.h"

namespace plumb::reco {
namespace {

// |x| of normal noise kept within +-window, as a RANSAC plane's inliers are.
std::vector<double> cutNormal(double sigma, double window, int count, std::uint64_t seed) {
  Random random(seed);
  std::vector<double> kept;
  while (static_cast<int>(kept.size()) < count) {
    const double x = std::abs(sigma * random.gaussian());
    if (x <= window) kept.push_back(x);
  }
  return kept;
}

// The median of |x| understates sigma by a third when the window is sigma: the correction for
// the cut gives sigma back within 5 % (5,000 residuals) from a window of 1 to 4 sigma, and
// within 10 % at half a sigma, where the residuals spread almost evenly and tell little.
TEST(NoiseThreshold, TheCutOffNormalGivesItsSigmaBack) {
  for (const double k : {0.5, 1.0, 2.0, 3.0, 4.0}) {
    const auto residuals = cutNormal(0.02, k * 0.02, 5000, 11);
    EXPECT_NEAR(truncatedNormalSigma(residuals, k * 0.02), 0.02, k < 1.0 ? 0.002 : 0.001) << "window " << k << " sigma";
  }
  EXPECT_EQ(truncatedNormalSigma({}, 0.01), 0.0);
}

//   residuals: noise sigma, plus a fifth of the points from a surface 4 sigma behind
//   |  noise  |       | behind |
//   0   sigma   2s   3s   4s   5s    window = 6 sigma
// The first estimate takes the surface behind for noise; within 2 sigma it does not count.
TEST(NoiseThreshold, ASurfaceAFewSigmaBehindIsNotNoise) {
  Random random(12);
  const double sigma = 0.01, window = 0.06;
  std::vector<double> residuals = cutNormal(sigma, window, 4000, 13);
  for (int i = 0; i < 1000; ++i) residuals.push_back(std::abs(4.0 * sigma + sigma * random.gaussian()));
  EXPECT_GT(truncatedNormalSigma(residuals, window), 1.3 * sigma);
  EXPECT_NEAR(robustNoiseSigma(residuals, window), sigma, 0.1 * sigma);
}

//        z
//        |  wall x = 0
//        +------ y
//       /  floor z = 0
//      x
// Patches on two planes meeting along an edge, 3 mm noise: the median patch is planar.
TEST(NoiseThreshold, PatchesAcrossAnEdgeDoNotRaiseTheMedian) {
  Random random(14);
  const double sigma = 0.003;
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i < 3000; ++i) {
    points.emplace_back(sigma * random.gaussian(), random.uniform(), random.uniform());
    points.emplace_back(random.uniform(), random.uniform(), sigma * random.gaussian());
  }
  EXPECT_NEAR(localNoiseSigma(points, 0.15), sigma, 0.15 * sigma);
  EXPECT_EQ(localNoiseSigma(std::vector<Eigen::Vector3d>(5, Eigen::Vector3d::Zero()), 0.1), 0.0);
}

TEST(NoiseThreshold, ThresholdIsThreeSigmaWithinItsBounds) {
  EXPECT_DOUBLE_EQ(thresholdForNoise(0.01), 0.03);
  EXPECT_DOUBLE_EQ(thresholdForNoise(0.0), kMinThreshold);
  EXPECT_DOUBLE_EQ(thresholdForNoise(1.0), kMaxThreshold);
}

}  // namespace
}  // namespace plumb::reco
