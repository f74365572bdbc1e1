// The laser-scanner simulator.
//
//   1. For each station, azimuth column and elevation row, cast the nominal beam into the scene
//      (scene-local frame: the scene's rotation is undone on the beam instead of on the scene).
//   2. No hit within the maximum range: a miss. A hit lost to dropout: counted and skipped.
//   3. Measurement: true hit + range error along the beam + lateral (angular) error across it.
//   4. Attributes: the surface's colour with a little jitter, intensity from reflectivity and
//      the cosine of the incidence angle.
// Blocks of columns run in parallel on oneTBB and reach the sink in order.

#include "reco/sim/scanner.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_pipeline.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <memory>
#include <mutex>
#include <numbers>

#include "engine/core/random.h"
#include "reco/sim/ray_caster.h"

namespace plumb::reco::sim {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;
// About this many beams per block: large enough to amortise scheduling, small enough to keep
// both cores busy and memory in flight low.
constexpr std::uint64_t kBeamsPerBlock = 16384;
constexpr double kPilotStepDeg = 0.5;

struct Trig {
  double cos_value, sin_value;
};

// Per-station constants of the pattern.
struct Beams {
  std::vector<Trig> azimuth;    // per column, world frame
  std::vector<Trig> elevation;  // per row
  Trig rotation;                // of the scene about z
};

Beams makeBeams(const ScanPattern& pattern, double rotation_deg) {
  Beams beams;
  beams.azimuth.resize(pattern.columns);
  for (std::uint32_t c = 0; c < pattern.columns; ++c) {
    const double a = c * pattern.azimuthStepDeg() * kDegree;
    beams.azimuth[c] = {std::cos(a), std::sin(a)};
  }
  beams.elevation.resize(pattern.rows);
  for (std::uint32_t r = 0; r < pattern.rows; ++r) {
    const double e = (pattern.min_elevation_deg + (r + 0.5) * pattern.elevationStepDeg()) * kDegree;
    beams.elevation[r] = {std::cos(e), std::sin(e)};
  }
  beams.rotation = {std::cos(rotation_deg * kDegree), std::sin(rotation_deg * kDegree)};
  return beams;
}

// World direction -> scene-local direction: rotate by -rotation about z.
Eigen::Vector3d toLocal(const Eigen::Vector3d& world, const Trig& rotation) {
  return {rotation.cos_value * world.x() + rotation.sin_value * world.y(),
          -rotation.sin_value * world.x() + rotation.cos_value * world.y(), world.z()};
}

struct Block {
  std::uint32_t station;
  std::uint32_t first_column;
  std::uint32_t column_count;
  std::uint64_t index;  // global block number: the seed of its generator
};

struct BlockResult {
  std::vector<ScanPoint> points;
  ScanCounts counts;
};

std::uint8_t jitterChannel(std::uint8_t value, std::uint64_t bits) {
  const int jittered = value + static_cast<int>(bits & 7u) - 4;
  return static_cast<std::uint8_t>(std::clamp(jittered, 0, 255));
}

void scanBlock(const Scene& scene, const RayCaster& caster, const Eigen::Vector3d& station_local, const Beams& beams,
               const ScannerSettings& settings, const Block& block, BlockResult& out) {
  Random random(mixSeed(settings.seed, block.index));
  const double noise2 = settings.noise_m * settings.noise_m;
  const double range_ppm = settings.range_noise_ppm * 1e-6;
  const double angular_rad = settings.angular_noise_urad * 1e-6;
  const Trig& rotation = beams.rotation;
  const Eigen::Vector3d station_world(rotation.cos_value * station_local.x() - rotation.sin_value * station_local.y(),
                                      rotation.sin_value * station_local.x() + rotation.cos_value * station_local.y(),
                                      station_local.z());

  for (std::uint32_t c = block.first_column; c < block.first_column + block.column_count; ++c) {
    const Trig az = beams.azimuth[c];
    const Eigen::Vector3d across_azimuth(-az.sin_value, az.cos_value, 0.0);
    for (const Trig& el : beams.elevation) {
      ++out.counts.rays;
      const Eigen::Vector3d direction(el.cos_value * az.cos_value, el.cos_value * az.sin_value, el.sin_value);
      const Eigen::Vector3d local_direction = toLocal(direction, rotation);
      RayHit hit;
      if (!caster.intersect(station_local, local_direction, settings.max_range_m, hit)) {
        ++out.counts.misses;
        continue;
      }
      if (settings.dropout > 0.0 && random.uniform() < settings.dropout) {
        ++out.counts.dropped;
        continue;
      }
      const Quad& quad = scene.quads[hit.quad];
      const Material& material = scene.materials[quad.material];
      const double range = hit.distance;

      const double range_sigma = std::sqrt(noise2 + range_ppm * range * range_ppm * range);
      const double lateral_sigma = std::sqrt(noise2 + angular_rad * range * angular_rad * range);
      const Eigen::Vector3d across_elevation(-el.sin_value * az.cos_value, -el.sin_value * az.sin_value, el.cos_value);
      const double range_error = range_sigma * random.gaussian();
      const double elevation_error = lateral_sigma * random.gaussian();
      const double azimuth_error = lateral_sigma * random.gaussian();

      ScanPoint point;
      point.position = station_world + (range + range_error) * direction + elevation_error * across_elevation +
                       azimuth_error * across_azimuth;
      point.plane = quad.plane;
      const double incidence_cos = std::abs(local_direction[quad.axis]);
      const double strength = material.reflectivity * (0.15 + 0.85 * incidence_cos) * (0.98 + 0.04 * random.uniform());
      point.intensity = static_cast<std::uint16_t>(std::clamp(strength * 65535.0, 0.0, 65535.0));
      const std::uint64_t bits = random.next();
      point.rgb = {jitterChannel(material.rgb[0], bits), jitterChannel(material.rgb[1], bits >> 8),
                   jitterChannel(material.rgb[2], bits >> 16)};
      point.station = static_cast<std::uint8_t>(block.station);
      out.points.push_back(point);
      ++out.counts.returns;
    }
  }
}

void add(ScanCounts& total, const ScanCounts& part) {
  total.rays += part.rays;
  total.returns += part.returns;
  total.misses += part.misses;
  total.dropped += part.dropped;
}

}  // namespace

ScanPattern ScanPattern::fromStep(double step_deg) {
  assert(step_deg > 0.0 && "angular step must be positive");
  ScanPattern pattern;
  pattern.columns = static_cast<std::uint32_t>(std::max(1.0, std::round(360.0 / step_deg)));
  pattern.rows = static_cast<std::uint32_t>(
      std::max(1.0, std::round((pattern.max_elevation_deg - pattern.min_elevation_deg) / step_deg)));
  return pattern;
}

ScanCounts scan(const Scene& scene, const std::vector<Eigen::Vector3d>& stations, const ScannerSettings& settings,
                const ScanSink& sink, const std::function<void(double)>& progress) {
  assert(stations.size() <= 255 && "station numbers are stored in one byte");
  const RayCaster caster(scene);
  const Beams beams = makeBeams(settings.pattern, settings.rotation_deg);
  const std::uint32_t columns = settings.pattern.columns;
  const std::uint32_t columns_per_block =
      static_cast<std::uint32_t>(std::max<std::uint64_t>(1, kBeamsPerBlock / settings.pattern.rows));
  const std::uint32_t blocks_per_station = (columns + columns_per_block - 1) / columns_per_block;
  const std::uint64_t block_count = std::uint64_t{blocks_per_station} * stations.size();

  ScanCounts total;
  std::uint64_t next_block = 0;
  std::uint64_t blocks_done = 0;
  // The blocks' results circulate through a pool the pipeline's live tokens never outnumber:
  // oneTBB does not destroy the items in flight when a filter throws (a sink that stops the
  // scan), so they must own nothing themselves.
  constexpr std::size_t kLiveBlocks = 8;
  std::array<BlockResult, kLiveBlocks> pool;
  std::vector<BlockResult*> free_results;
  for (BlockResult& result : pool) free_results.push_back(&result);
  std::mutex free_mutex;
  tbb::parallel_pipeline(
      kLiveBlocks,
      tbb::make_filter<void, Block>(tbb::filter_mode::serial_in_order, [&](tbb::flow_control& control) -> Block {
        if (next_block == block_count) {
          control.stop();
          return {};
        }
        const std::uint64_t index = next_block++;
        const auto station = static_cast<std::uint32_t>(index / blocks_per_station);
        const auto first = static_cast<std::uint32_t>(index % blocks_per_station) * columns_per_block;
        return {station, first, std::min(columns_per_block, columns - first), index};
      }) & tbb::make_filter<Block, BlockResult*>(tbb::filter_mode::parallel, [&](const Block& block) {
        BlockResult* result = nullptr;
        {
          const std::lock_guard lock(free_mutex);
          result = free_results.back();
          free_results.pop_back();
        }
        result->points.clear();
        result->counts = {};
        result->points.reserve(std::uint64_t{block.column_count} * settings.pattern.rows);
        scanBlock(scene, caster, stations[block.station], beams, settings, block, *result);
        return result;
      }) & tbb::make_filter<BlockResult*, void>(tbb::filter_mode::serial_in_order, [&](BlockResult* result) {
        add(total, result->counts);
        sink(result->points);
        if (progress) progress(static_cast<double>(++blocks_done) / static_cast<double>(block_count));
        const std::lock_guard lock(free_mutex);
        free_results.push_back(result);
      }));
  return total;
}

ScanPattern patternForTarget(const Scene& scene, const std::vector<Eigen::Vector3d>& stations,
                             const ScannerSettings& settings, std::uint64_t target_points) {
  assert(target_points > 0);
  const ScanPattern pilot = ScanPattern::fromStep(kPilotStepDeg);
  const RayCaster caster(scene);
  const Beams beams = makeBeams(pilot, settings.rotation_deg);

  // Beams that return per beam cast, summed over stations; noise-free, as dropout is applied
  // analytically below.
  double returns_per_beam = 0.0;
  for (const Eigen::Vector3d& station : stations) {
    const std::uint64_t hits = tbb::parallel_reduce(
        tbb::blocked_range<std::uint32_t>(0, pilot.columns), std::uint64_t{0},
        [&](const tbb::blocked_range<std::uint32_t>& range, std::uint64_t count) {
          for (std::uint32_t c = range.begin(); c != range.end(); ++c) {
            for (const Trig& el : beams.elevation) {
              const Eigen::Vector3d direction(el.cos_value * beams.azimuth[c].cos_value,
                                              el.cos_value * beams.azimuth[c].sin_value, el.sin_value);
              RayHit hit;
              if (caster.intersect(station, toLocal(direction, beams.rotation), settings.max_range_m, hit)) ++count;
            }
          }
          return count;
        },
        std::plus<>());
    returns_per_beam += static_cast<double>(hits) / static_cast<double>(pilot.raysPerStation());
  }
  returns_per_beam *= 1.0 - settings.dropout;
  if (returns_per_beam <= 0.0) return ScanPattern::fromStep(kPilotStepDeg);

  // rays = columns * rows with columns / rows = 360 / elevation span (square steps); then the
  // rows are chosen for the exact target, so rounding costs at most half a row of points.
  const double span = pilot.max_elevation_deg - pilot.min_elevation_deg;
  const double rays = static_cast<double>(target_points) / returns_per_beam;
  const double step = std::sqrt(360.0 * span / rays);
  ScanPattern pattern = ScanPattern::fromStep(step);
  pattern.rows = static_cast<std::uint32_t>(std::max(1.0, std::round(rays / pattern.columns)));
  return pattern;
}

}  // namespace plumb::reco::sim
