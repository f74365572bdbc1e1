#pragma once
// The statistical limit of a simulated scan (docs/simulator.md): least-squares planes fitted on
// all the points the simulator labels with each true plane (the PLY's plane_id), and how far a
// fit on those points is expected to be off. What the evaluation (tests/eval) and the end-to-end
// tests judge the grower's planes and corners against.

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "reco/plane_regression.h"

namespace plumb::test {

// One regression per true plane (plane_count of them), over every point of the PLY that
// `plumb simulate` wrote at `path`, referenced at `reference` (a point near the scan, so that the
// sums stay exact at survey coordinates). `each_point`, when set, sees every point and its label.
// io::PointReader drops the simulator's plane_id, so this reads the simulator's own layout:
// binary little-endian, one vertex element, scalar properties. Throws plumb::Error naming the file.
std::vector<reco::PlaneRegression> fitTruePlanes(
    const std::string& path, std::size_t plane_count, const Eigen::Vector3d& reference,
    const std::function<void(const Eigen::Vector3d&, std::uint32_t)>& each_point = {});

// The standard deviation of the fitted plane's signed distance at `point`: sigma^2 / N for the
// offset at the centroid, plus the tilt's share growing with the distance from it along each
// in-plane axis (sigma^2 / (N lambda_i)); sigma is the fit's own RMS residual.
double planeStandardErrorAt(const reco::PlaneRegression& fit, const Eigen::Vector3d& point);

// The standard deviation of the fitted plane's normal direction, radians (both in-plane axes).
double planeAngleStandardError(const reco::PlaneRegression& fit);

// The RMS error expected of the corner where the three fitted planes meet near `corner`: each
// plane's error at the corner carried through the intersection.
double cornerStandardError(const std::array<const reco::PlaneRegression*, 3>& fits, const Eigen::Vector3d& corner);

// How many standard errors of the statistical limit the end-to-end tests (ui, cli) allow a grown
// corner or plane: "a few times the limit" (issue 25, point 5), where they accepted 5 mm before,
// 30 to 70 times the limit at 2 mm noise.
constexpr double kEndToEndLimitFactor = 5.0;

// A corner of a simulated scan against its statistical limit: the truth's corner, the corner of
// its three planes fitted on all their points, and the RMS error expected of that fit
// (cornerStandardError).
struct CornerLimit {
  Eigen::Vector3d truth;
  Eigen::Vector3d fitted;
  double standard_error_m = 0;
};

// A plane of a simulated scan against its statistical limit: the truth's plane fitted on all its
// points, with the standard errors of its distance at a point and of its normal.
struct PlaneLimit {
  Eigen::Vector3d normal;  // the truth's, unit
  double d = 0;            // the truth's: normal . x + d = 0
  double distance_error_m = 0;
  double angle_error_rad = 0;
};

// A scan `plumb simulate` wrote (the PLY and its --truth file) with every true plane fitted on
// all its points, once: the limits of its corners and planes.
class SimulatedTruth {
 public:
  SimulatedTruth(const std::string& points_path, const std::string& truth_path);

  // The truth's corner at `position` (within 1 mm); throws when it lists none there.
  CornerLimit cornerLimit(const Eigen::Vector3d& position) const;
  // The truth's plane `name`, its errors taken at `point`.
  PlaneLimit planeLimit(const std::string& name, const Eigen::Vector3d& point) const;

 private:
  std::string truth_path_;
  struct TruePlane {
    std::string name;
    Eigen::Vector3d normal;
    double d;
  };
  std::vector<TruePlane> planes_;
  struct TrueCorner {
    Eigen::Vector3d position;
    std::array<std::uint32_t, 3> planes;
  };
  std::vector<TrueCorner> corners_;
  std::vector<reco::PlaneRegression> fits_;
};

}  // namespace plumb::test
