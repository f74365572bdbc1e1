#pragma once
// A reader that passes on every stride-th point of another: a quick preview of a big file (the
// viewer shows one while the whole file is imported). The choice goes by a point's index among
// the points the inner reader delivers, so every pass over the file (the octree builder reads it
// three times) sees the same points. counts().delivered counts the points passed on,
// counts().non_finite what the inner reader skipped; declared_points is the header's count
// divided by the stride.

#include <cstdint>
#include <memory>

#include "engine/io/point_reader.h"

namespace plumb::io {

class SampledReader final : public PointReader {
 public:
  // Takes over `inner`; `stride` >= 1 (1 passes everything on).
  SampledReader(std::unique_ptr<PointReader> inner, std::uint64_t stride);

  bool read(PointBatch& batch, std::size_t max_points) override;

 private:
  std::unique_ptr<PointReader> inner_;
  std::uint64_t stride_;
  std::uint64_t index_ = 0;  // of the next point the inner reader delivers
  PointBatch scratch_;
};

}  // namespace plumb::io
