#pragma once
// The robust final fit of a grown plane: an M-estimate with Tukey's biweight, by iteratively
// reweighted least squares, in place of the least-squares fit of the points the growth accepted.
//
// Why: the growth accepts a point within 2.25 times the plane's RMS of the plane as it is at that
// moment, and never revisits the choice. Even re-centred on the final plane, such a hard window is
// a poor estimator on Gaussian noise: the RMS of the accepted points is itself truncated, so the
// window settles at 1.94 sigma, a skipped mean of 71 % efficiency, and the plane is sqrt(1 / 0.71)
// = 1.19 times as uncertain as the least-squares fit of all the surface's points. The biweight at
// 3.5 sigma has 86 % efficiency (1.08 times), while a neighbouring surface's strip, whose points
// lie all on one side of the plane and spread evenly over the window, pulls it no harder: its
// weighted first moment is c^2 / 6 against the hard window's c^2 / 2 (2.0 against 1.9 sigma^2).
// The region grower applies it to the settled segments (region_grower.h, GrowOptions::refine_c),
// and its last fit gives the points away from a segment's border full weight
// (interior_points.h): the strips lie along the border, and inside the efficiency is all.

#include <Eigen/Core>
#include <span>
#include <vector>

#include "reco/plane.h"

namespace plumb::reco {

// Tukey's biweight of a residual: (1 - (d / window)^2)^2 within the window, 0 outside.
double biweight(double residual, double window);

// The standard deviation of Gaussian residuals, robustly: 1.4826 times their median absolute
// value. Takes the absolute residuals by value (it reorders them); 0 for none.
double robustScale(std::vector<double> absolute_residuals);

// The weighted least-squares plane: weighted centroid and covariance, then plane synthesis
// (plane_regression.h). Points of weight 0 count for nothing; invalid with fewer than three of
// positive weight. The sums are taken relative to the first point, for UTM coordinates.
Plane fitWeightedPlane(std::span<const Eigen::Vector3d> points, std::span<const double> weights);

}  // namespace plumb::reco
