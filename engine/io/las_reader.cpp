// LAS and LAZ reader (ASPRS LAS Specification 1.4 R15, 2019; also reads LAS 1.0 to 1.3, whose
// headers are prefixes of the 1.4 one). Point data record formats 0 to 10 uncompressed; LAZ
// (compressed LAS) written with the point-wise LASzip coder, point formats 0 to 3, or the layered
// one, point formats 6 to 8 (laz_point_decompressor.h).
//
//   1. Read and check the public header block and the laszip VLR (las_header.h, steps 1 to 4
//      there): the layout, the point count, scale, offset and bounds; that the file holds every
//      declared record (LAZ: that the chunk table covers them), so that a truncated file fails
//      before any point is delivered.
//   2. Seek to the point data (skipping the VLRs whatever their number and size) and stream the
//      records in chunks through FileSource (LAZ: decompressed into the same record bytes),
//      decoding x y z (X * scale + offset), intensity and, for formats 2 3 5 7 8 10, colour
//      (already 16-bit in LAS). Bytes beyond the format's standard size ("extra bytes") are
//      skipped; whatever follows the last declared record (EVLRs in 1.4, waveform data, LAZ's
//      chunk table) is not point data and is never read as points.
//   3. LAZ with a chunk table of several chunks: decoded a few chunks ahead on oneTBB's workers
//      (laz_chunk_window.h), the same records in the same order, the same errors at the same
//      record; without a table or with one chunk, as the records are read.

#include "engine/io/las_reader.h"

#include <tbb/task_arena.h>

#include <algorithm>
#include <cassert>
#include <memory>

#include "engine/io/file_source.h"
#include "engine/io/las_header.h"
#include "engine/io/laz_chunk_window.h"
#include "engine/io/laz_point_decompressor.h"
#include "engine/io/point_reader.h"

namespace plumb::io {
namespace {

// LAZ files of fewer points decode on the reading thread unless LasReadOptions asks otherwise.
constexpr std::uint64_t kMinParallelPoints = std::uint64_t{1} << 16;

// Read chunk: enough records to amortise the calls, bounded in bytes whatever the record length.
constexpr std::size_t kChunkBytes = std::size_t{1} << 20;

std::vector<std::string> ignoredFields(std::uint8_t format, const LasFormatLayout& layout, std::size_t extra_bytes) {
  std::vector<std::string> fields{"return_number",       "number_of_returns", "scan_direction",
                                  "edge_of_flight_line", "classification",    "classification_flags"};
  if (format >= 6) fields.emplace_back("scanner_channel");
  fields.emplace_back(format >= 6 ? "scan_angle" : "scan_angle_rank");
  fields.emplace_back("user_data");
  fields.emplace_back("point_source_id");
  if (layout.has_gps_time) fields.emplace_back("gps_time");
  if (layout.has_nir) fields.emplace_back("nir");
  if (layout.has_wave_packet) fields.emplace_back("wave_packet");
  if (extra_bytes > 0) fields.push_back("extra bytes (" + std::to_string(extra_bytes) + " per point)");
  return fields;
}

class LasReader final : public LasPointReader {
 public:
  LasReader(const std::string& path, const LasReadOptions& options) : LasPointReader(path), source_(path) {
    readHeader(options);
    source_.seek(header_.point_offset);
    chunk_records_ = std::max<std::size_t>(1, kChunkBytes / header_.record_length);
  }

  bool read(PointBatch& batch, std::size_t max_points) override {
    assert(max_points > 0 && "read() needs room for at least one point; pass max_points >= 1");
    batch.clear();
    while (batch.size() < max_points && next_record_ < header_.point_count) {
      const std::size_t records = readRecords(records_, std::min(max_points - batch.size(), chunk_records_));
      // Integers cannot be NaN, but a huge scale can overflow to infinity: deliver() counts those.
      for (std::size_t i = 0; i < records; ++i) {
        deliver(batch, decodeLasPoint(records_.data() + i * header_.record_length, header_));
      }
    }
    return batch.size() > 0;
  }

  std::size_t recordLength() const override { return header_.record_length; }

  std::size_t readRecords(std::vector<std::byte>& records, std::size_t max_records) override {
    assert(max_records > 0 && "readRecords() needs room for at least one record; pass max_records >= 1");
    const auto count =
        static_cast<std::size_t>(std::min<std::uint64_t>(max_records, header_.point_count - next_record_));
    records.resize(count * header_.record_length);
    if (window_) {
      window_->decode(records);
    } else if (laz_) {
      laz_->decode(records);
    } else {
      source_.readExactly(records, "the point records");
    }
    next_record_ += count;
    return count;
  }

 private:
  void readHeader(const LasReadOptions& options);

  FileSource source_;
  LasHeader header_;
  std::uint64_t next_record_ = 0;
  std::size_t chunk_records_ = 1;
  std::vector<std::byte> records_;
  std::unique_ptr<LazPointDecompressor> laz_;  // LAZ only; reads through source_
  std::unique_ptr<LazChunkWindow> window_;     // LAZ decoded in parallel, in place of laz_
};

// Several chunks in flight when asked and worth it: a table (else a chunk's start is only known
// once the previous one is decoded), two chunks or more, none too large to buffer.
std::size_t chunksInFlight(const LasReadOptions& options, const LazChunkTable& table, std::size_t record_length) {
  if (!table.present || table.chunks.size() < 2) return 1;
  for (const LazChunk& chunk : table.chunks) {
    if (chunk.points > LazChunkWindow::kMaxChunkBytes / record_length) return 1;
  }
  if (options.laz_chunks_in_flight != 0) return options.laz_chunks_in_flight;
  // A small file decodes in about a millisecond: a file handle and fresh models per chunk, and the
  // hand-over between threads, would cost more than they save.
  std::uint64_t points = 0;
  for (const LazChunk& chunk : table.chunks) points += chunk.points;
  if (points < kMinParallelPoints) return 1;
  return 2 * static_cast<std::size_t>(std::max(1, tbb::this_task_arena::max_concurrency()));
}

void LasReader::readHeader(const LasReadOptions& options) {
  header_ = readLasHeader(source_);
  if (header_.compressed()) {
    laz_ = std::make_unique<LazPointDecompressor>(source_, *header_.laszip, header_.point_offset,
                                                  header_.compressed_end, header_.record_length, header_.point_count);
    if (const std::size_t in_flight = chunksInFlight(options, laz_->table(), header_.record_length); in_flight > 1) {
      window_ = std::make_unique<LazChunkWindow>(source_.path(), *header_.laszip, laz_->table(), header_.record_length,
                                                 in_flight);
      laz_.reset();
    }
  }
  info_.format = std::string(header_.compressed() ? "LAZ " : "LAS ") + header_.version() + " point format " +
                 std::to_string(header_.format);
  info_.declared_points = header_.point_count;
  info_.declared_bounds = header_.bounds;
  info_.attributes.colour = header_.layout.has_colour;
  info_.attributes.intensity = true;
  info_.ignored_fields = ignoredFields(header_.format, header_.layout, header_.record_length - header_.layout.bytes);
}

}  // namespace

std::unique_ptr<PointReader> openLas(const std::string& path) {
  return std::make_unique<LasReader>(path, LasReadOptions{});
}

std::unique_ptr<LasPointReader> openLasRecords(const std::string& path, const LasReadOptions& options) {
  return std::make_unique<LasReader>(path, options);
}

}  // namespace plumb::io
