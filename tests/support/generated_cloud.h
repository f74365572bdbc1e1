#pragma once
// Point clouds made on the fly for octree tests and benchmarks: a PointReader over a generator,
// so that clouds of any size need no file.

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "engine/io/point_reader.h"
#include "engine/lod/octree_builder.h"

namespace plumb::test {

// Point i of a cloud of `count` points.
using PointGenerator = std::function<io::PointRecord(std::uint64_t i)>;

// `scans`: the names of the scans the generated file holds, as E57 reports its data3D (the
// generator sets each point's PointRecord::scan); empty: a file of one scan.
class GeneratedReader final : public io::PointReader {
 public:
  GeneratedReader(std::uint64_t count, PointGenerator generator, std::vector<std::string> scans = {})
      : io::PointReader("generated"), count_(count), generator_(std::move(generator)) {
    info_.format = "generated";
    info_.declared_points = count;
    info_.attributes.colour = true;
    info_.attributes.intensity = true;
    info_.scans = std::move(scans);
  }

  // As a LAS header states them.
  void declareBounds(const io::Bounds& bounds) { info_.declared_bounds = bounds; }

  bool read(io::PointBatch& batch, std::size_t max_points) override {
    batch.clear();
    while (batch.size() < max_points && next_ < count_) deliver(batch, generator_(next_++));
    return !batch.points.empty();
  }

 private:
  std::uint64_t count_;
  PointGenerator generator_;
  std::uint64_t next_ = 0;
};

inline lod::BuildSource generatedSource(std::uint64_t count, PointGenerator generator, std::string name = "generated",
                                        std::vector<std::string> scans = {}) {
  return {std::move(name),
          [count, generator, scans] { return std::make_unique<GeneratedReader>(count, generator, scans); }};
}

// A unique 64-bit id carried in the colour and intensity channels, to follow points through a build.
inline io::PointRecord withId(double x, double y, double z, std::uint64_t id) {
  return {x,
          y,
          z,
          {static_cast<std::uint16_t>(id), static_cast<std::uint16_t>(id >> 16), static_cast<std::uint16_t>(id >> 32)},
          static_cast<std::uint16_t>(id >> 48)};
}
inline std::uint64_t idOf(const std::array<std::uint16_t, 3>& rgb, std::uint16_t intensity) {
  return std::uint64_t{rgb[0]} | (std::uint64_t{rgb[1]} << 16) | (std::uint64_t{rgb[2]} << 32) |
         (std::uint64_t{intensity} << 48);
}

// A deterministic hash of i into [0, 1): jitter for generated points.
inline double unitHash(std::uint64_t i, std::uint64_t salt) {
  std::uint64_t x = i * 0x9E3779B97F4A7C15ULL + salt * 0xD1B54A32D192ED03ULL;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ULL;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBULL;
  x ^= x >> 31;
  return static_cast<double>(x >> 11) * 0x1.0p-53;
}

}  // namespace plumb::test
