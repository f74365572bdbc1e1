#pragma once
// A terrestrial laser scanner: a regular azimuth/elevation pattern cast from each station into a
// Scene, with range and angular noise, a maximum range, dropout, colour per surface and
// intensity by incidence angle. docs/simulator.md explains the noise model.
//
// Deterministic for a seed: the work is cut into blocks of azimuth columns, each with its own
// generator, so the output does not depend on the number of threads.

#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include "reco/sim/scene.h"

namespace plumb::reco::sim {

// The scan pattern: `columns` azimuths over the full turn and `rows` elevations over
// [min_elevation_deg, max_elevation_deg], sampled at the centres of the rows.
struct ScanPattern {
  std::uint32_t columns = 3600;
  std::uint32_t rows = 1500;
  double min_elevation_deg = -60.0;  // the scanner's base hides the cone below
  double max_elevation_deg = 90.0;

  double azimuthStepDeg() const { return 360.0 / columns; }
  double elevationStepDeg() const { return (max_elevation_deg - min_elevation_deg) / rows; }
  std::uint64_t raysPerStation() const { return std::uint64_t{columns} * rows; }

  // The pattern whose steps are closest to `step_deg` in both directions.
  static ScanPattern fromStep(double step_deg);
};

struct ScannerSettings {
  ScanPattern pattern;
  // Isotropic 1-sigma point noise: applied along the beam (range) and across it (angular), so
  // that the distance of a point to its true surface has this RMS at any incidence angle.
  double noise_m = 0.002;
  // Additional range noise proportional to the range, in parts per million (1 ppm = 1 mm at 1 km).
  double range_noise_ppm = 0.0;
  // Additional angular noise in microradians (1 urad = 1 mm lateral at 1 km).
  double angular_noise_urad = 0.0;
  double max_range_m = 80.0;
  double dropout = 0.0;  // probability that a return is lost, [0, 1)
  std::uint64_t seed = 1;
  // The scene turns by this angle about the vertical (through its origin) before scanning.
  double rotation_deg = 0.0;
};

struct ScanPoint {
  // World position without any output offset: the scene rotated by rotation_deg.
  Eigen::Vector3d position;
  PlaneId plane;  // the true plane the beam hit
  std::uint16_t intensity;
  std::array<std::uint8_t, 3> rgb;
  std::uint8_t station;
};

struct ScanCounts {
  std::uint64_t rays = 0;
  std::uint64_t returns = 0;  // points produced
  std::uint64_t misses = 0;   // beams that hit nothing within max_range_m
  std::uint64_t dropped = 0;  // returns lost to dropout
};

// Receives the points block by block, in a fixed order (station, then azimuth), from one thread
// at a time. The span is valid only during the call.
using ScanSink = std::function<void(std::span<const ScanPoint>)>;

// Scans `scene` from `stations` (scene-local positions, at most 255). `sink` may throw to stop.
// `progress`, when set, is called after each block with the fraction done, on the sink's thread.
ScanCounts scan(const Scene& scene, const std::vector<Eigen::Vector3d>& stations, const ScannerSettings& settings,
                const ScanSink& sink, const std::function<void(double)>& progress = {});

// The pattern that makes `scan` produce about `target_points` points: a pilot scan at 0.5
// degrees measures the fraction of beams that return, then the pattern is sized to match.
ScanPattern patternForTarget(const Scene& scene, const std::vector<Eigen::Vector3d>& stations,
                             const ScannerSettings& settings, std::uint64_t target_points);

}  // namespace plumb::reco::sim
