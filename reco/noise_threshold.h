#pragma once
// The plane threshold t_p from the data: the noise of the seed planes, measured robustly, and a
// threshold of kThresholdSigmas times it where that is more than the default t_p (the
// evaluation's t_p = 3 sigma, never below 20 mm). A user who does not know the scanner's noise
// gets the planes of one who does. docs/parameters.md, "t_p from the data"; the grower's use in
// region_grower.cpp, seedPlanesMeasuringThreshold.
//
//   1. The residuals of each seed plane's inliers (all within the window t_p used to find them).
//   2. Their median absolute value, m, is that of a normal distribution cut off at +-t_p: where
//      t_p is under about 3 sigma, m understates sigma (at t_p = sigma, by a third). Solve
//      sigma * q(t_p / sigma) = m for sigma, where q(k) is the median of |x| for a standard
//      normal x cut off at +-k: q(k) = Phi^-1(1/4 + Phi(k) / 2).
//   3. The same within a window of 2 sigma, again until sigma settles: a surface a few sigma
//      behind the plane (a door leaf in its recess, at 30 mm noise inside a 90 mm window) or the
//      strips of a neighbouring surface widen the residuals in the outer part of the window;
//      within 2 sigma the noise dominates (at 30 mm noise the first estimate was 43 mm).
//   4. t_p = kThresholdSigmas x sigma, within [kMinThreshold, kMaxThreshold].

#include <Eigen/Core>
#include <span>

namespace plumb::reco {

constexpr double kThresholdSigmas = 3.0;
constexpr double kMinThreshold = 0.001;  // metres: below, the octree's float offsets show
constexpr double kMaxThreshold = 0.2;    // metres: beyond, no plane is a plane

// Step 2: the sigma of a zero-mean normal whose values cut off at +-window have absolute values
// `abs_residuals` (each in [0, window]). At most 8 x window where the residuals spread evenly
// over the window (the window cuts off most of the distribution). 0 for no residual.
double truncatedNormalSigma(std::span<const double> abs_residuals, double window);

// The noise of the surfaces around: the median, over up to 64 of `points` spread through them,
// of the RMS distance of the points within `radius` of each from their least-squares plane (the
// smallest eigenvalue's root, with n / (n - 3) for the three fitted parameters). No threshold
// goes in: a patch across an edge or a corner gives more than the noise, and the median keeps
// the planar patches', which are most of them where the patch is a quarter of the seed sphere.
// 0 when no patch has 12 points.
double localNoiseSigma(std::span<const Eigen::Vector3d> points, double radius);

// Steps 2 and 3: the noise of residuals (absolute values) selected within +-window.
double robustNoiseSigma(std::span<const double> abs_residuals, double window);

// Step 4.
double thresholdForNoise(double sigma);

}  // namespace plumb::reco
