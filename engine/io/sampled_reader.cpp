#include "engine/io/sampled_reader.h"

#include <cassert>

namespace plumb::io {

SampledReader::SampledReader(std::unique_ptr<PointReader> inner, std::uint64_t stride)
    : PointReader(inner->path()), inner_(std::move(inner)), stride_(stride) {
  assert(stride_ >= 1 && "a stride of 0 would keep nothing: use 1 to keep every point");
  info_ = inner_->info();
  if (info_.declared_points) info_.declared_points = (*info_.declared_points + stride_ - 1) / stride_;
}

bool SampledReader::read(PointBatch& batch, std::size_t max_points) {
  batch.points.clear();
  batch.normals.clear();
  // Reads on until the batch holds something or the file ends, so a batch is empty only at the end.
  while (batch.points.empty()) {
    if (!inner_->read(scratch_, max_points)) break;
    const bool normals = scratch_.normals.size() == scratch_.points.size() && !scratch_.normals.empty();
    for (std::size_t i = 0; i < scratch_.points.size(); ++i, ++index_) {
      if (index_ % stride_ != 0) continue;
      batch.points.push_back(scratch_.points[i]);
      if (normals) batch.normals.push_back(scratch_.normals[i]);
    }
  }
  counts_.delivered += batch.points.size();
  counts_.non_finite = inner_->counts().non_finite;
  return !batch.points.empty();
}

}  // namespace plumb::io
