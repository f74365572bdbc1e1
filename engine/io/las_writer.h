#pragma once
// Streaming writer of LAS 1.2 files of point data record format 2 (position, intensity, colour),
// the format every point-cloud tool reads: ASPRS LAS Specification 1.2 (2008), section 2 (the
// public header block, table 4) and section 3 (point data record format 2, table 7).
//
// The point count and the bounds are known only after the last point, so finish() patches them
// into the header; the file appears atomically (AtomicFile). Coordinates are stored as 32-bit
// integers of `scale` metres around `offset`: a point beyond their reach is refused (plumb::Error
// naming the file), never wrapped.

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "engine/core/atomic_file.h"

namespace plumb::io {

struct LasWriterOptions {
  std::array<double, 3> offset{0.0, 0.0, 0.0};
  double scale = 1e-4;  // 0.1 mm: a 32-bit integer then reaches 214 km either side of the offset
  std::string software = "plumb";
};

class LasWriter {
 public:
  static constexpr std::size_t kRecordBytes = 26;             // point data record format 2
  static constexpr std::uint64_t kMaxPoints = 4'294'967'295;  // LAS 1.2 counts its points in 32 bits

  LasWriter(std::string path, const LasWriterOptions& options);

  // One point: world coordinates, 16-bit intensity and colour, and the point source ID (a
  // simulated point's true plane).
  void add(const std::array<double, 3>& position, std::uint16_t intensity, const std::array<std::uint16_t, 3>& rgb,
           std::uint16_t source_id);

  std::uint64_t pointCount() const { return count_; }
  std::uint64_t byteCount() const { return file_.size() + buffer_.size(); }

  // Patches the count and the bounds, flushes and fsyncs. commit() then moves the file into place.
  void finish();
  void commit();

 private:
  void flush();

  AtomicFile file_;
  LasWriterOptions options_;
  std::vector<std::byte> buffer_;
  std::uint64_t count_ = 0;
  std::array<double, 3> min_{}, max_{};
};

}  // namespace plumb::io
