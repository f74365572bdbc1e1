#include "engine/lod/octree_builder.h"

#include <fcntl.h>
#include <sys/resource.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_pipeline.h>
#include <tbb/task_arena.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <functional>
#include <limits>
#include <mutex>
#include <optional>
#include <thread>
#include <unordered_map>

#include "engine/core/atomic_file.h"
#include "engine/core/error.h"
#include "engine/lod/framing.h"
#include "engine/lod/node_indexer.h"
#include "engine/lod/octree_format.h"

namespace plumb::lod {
namespace {

using Clock = std::chrono::steady_clock;

constexpr std::size_t kReadBatchPoints = std::size_t{1} << 18;
// The counting grid: 128^3 cells, level 7.
constexpr std::uint32_t kCountLevel = 7;
constexpr std::size_t kCountCells = std::size_t{1} << (3 * kCountLevel);
// Bytes a point costs while its chunk is indexed: the point (28), the indexer's per-point
// scratch (cell key and its sort's copy 16, hash 4, order 4, partition flag and octant 2), slack
// for vector growth. The indexer's other scratch (the coarser points' keys) comes on top.
constexpr std::size_t kIndexBytesPerPoint = 72;
constexpr std::size_t kIndexerScratchBytes = std::size_t{16} << 20;
constexpr std::size_t kChunkBufferPoints = 8192;  // 256 KB of buffered writes per chunk
// Smaller chunks than this are not worth a task of their own.
constexpr std::uint64_t kMinChunkPoints = 1 << 20;

double secondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

std::size_t flatCell(const CellKey& key) {
  return (std::size_t{key.z} << (2 * key.level)) | (std::size_t{key.y} << key.level) | key.x;
}

// A temporary file of BuildPoints, unlinked at once: it vanishes with its descriptor.
class ChunkFile {
 public:
  ChunkFile(const std::string& output, const CellKey& key) : key_(key) {
    static std::atomic<unsigned> counter{0};
    const std::string name = output + ".chunk-" + std::to_string(::getpid()) + "-" + std::to_string(counter++);
    fd_ = ::open(name.c_str(), O_RDWR | O_CREAT | O_EXCL | O_CLOEXEC, 0600);
    if (fd_ < 0) throw fileError(name, "cannot create a temporary file (" + systemErrorText(errno) + ")");
    ::unlink(name.c_str());
    buffer_.reserve(kChunkBufferPoints);
  }
  ~ChunkFile() {
    if (fd_ >= 0) ::close(fd_);
  }
  ChunkFile(const ChunkFile&) = delete;
  ChunkFile& operator=(const ChunkFile&) = delete;

  const CellKey& key() const { return key_; }
  std::uint64_t count() const { return written_ + buffer_.size(); }

  void add(const BuildPoint& point) {
    buffer_.push_back(point);
    if (buffer_.size() == kChunkBufferPoints) flush();
  }

  // Appends a run of points: buffered when short, written straight through when long.
  void append(std::span<const BuildPoint> points) {
    if (buffer_.size() + points.size() > kChunkBufferPoints) flush();
    if (points.size() >= kChunkBufferPoints) {
      writeAt(written_, points);
      written_ += points.size();
    } else {
      buffer_.insert(buffer_.end(), points.begin(), points.end());
    }
  }

  void flush() {
    writeAt(written_, buffer_);
    written_ += buffer_.size();
    buffer_.clear();
  }

 private:
  void writeAt(std::uint64_t first, std::span<const BuildPoint> points) {
    const auto* data = reinterpret_cast<const char*>(points.data());
    std::size_t left = points.size_bytes();
    off_t at = static_cast<off_t>(first * sizeof(BuildPoint));
    while (left > 0) {
      const ssize_t done = ::pwrite(fd_, data, left, at);
      if (done < 0 && errno == EINTR) continue;
      if (done < 0)
        throw Error("cannot write a temporary chunk (" + systemErrorText(errno) + "); free some disk space");
      data += done;
      left -= static_cast<std::size_t>(done);
      at += done;
    }
  }

 public:
  // Points [first, first + out.size()) of the flushed file.
  void read(std::uint64_t first, std::span<BuildPoint> out) const {
    auto* data = reinterpret_cast<char*>(out.data());
    std::size_t left = out.size_bytes();
    off_t at = static_cast<off_t>(first * sizeof(BuildPoint));
    while (left > 0) {
      const ssize_t done = ::pread(fd_, data, left, at);
      if (done < 0 && errno == EINTR) continue;
      if (done <= 0) throw Error("cannot read back a temporary chunk (" + systemErrorText(errno) + ")");
      data += done;
      left -= static_cast<std::size_t>(done);
      at += done;
    }
  }

 private:
  CellKey key_;
  int fd_ = -1;
  std::vector<BuildPoint> buffer_;
  std::uint64_t written_ = 0;
};

// Many chunks each hold a descriptor: lift the soft limit to the hard one.
void raiseFileLimit() {
  rlimit limit{};
  if (::getrlimit(RLIMIT_NOFILE, &limit) == 0 && limit.rlim_cur < limit.rlim_max) {
    limit.rlim_cur = limit.rlim_max;
    ::setrlimit(RLIMIT_NOFILE, &limit);
  }
}

class Builder {
 public:
  explicit Builder(const BuildOptions& options) : options_(options) {
    if (options.sources.empty()) throw Error("no input files");
    budget_bytes_ = options.memory_mb << 20;
  }

  BuildReport run() {
    raiseFileLimit();
    // Made first, so that an output that cannot be written fails before the inputs are read
    // (a billion points take minutes a pass).
    AtomicFile output(options_.output);
    output_ = &output;
    auto start = Clock::now();
    // Inputs whose headers state their bounds (LAS, LAZ) need no pass for them.
    declared_ = declaredByHeaders();
    if (declared_) {
      settleCube(declared_->bounds);
    } else {
      scanBounds();
    }
    report_.seconds_bounds = secondsSince(start);

    start = Clock::now();
    std::vector<std::uint64_t> counts = countCells();
    if (declared_ && !declaredCubeHolds()) {
      // The headers' bounds were wrong or loose: count again in the cube of the points' own
      // bounds, which the count measured (the pass the headers saved, spent after all).
      report_.header_bounds_wrong = true;
      settleCube(header_.bounds);
      counts = countCells();
    }
    report_.bounds_from_headers = declared_.has_value();
    report_.seconds_counting = secondsSince(start);

    start = Clock::now();
    chooseChunks(counts);
    distribute();
    splitOversizedChunks();
    report_.seconds_distributing = secondsSince(start);

    start = Clock::now();
    const std::array<std::byte, kHeaderBytes> placeholder{};
    output.write(placeholder.data(), placeholder.size());
    indexChunks();
    indexTopLevels();
    finish(output);
    report_.seconds_indexing = secondsSince(start);
    return report_;
  }

 private:
  // What the inputs' headers state (declaredByHeaders).
  struct Declared {
    Box3 bounds;
    std::uint64_t points = 0;  // 0 when one does not say
  };

  // A batch of input points with what the parallel stage worked out about them.
  struct Batch {
    std::size_t source = 0;  // index of the input it came from
    io::PointBatch points;
    std::vector<std::uint32_t> cells;          // counting-grid cell of each point
    Box3 box{};                                // bounds of the batch
    std::optional<AxisHistograms> histograms;  // of the batch's coordinates (counting)
    std::vector<BuildPoint> by_chunk;          // the points grouped by chunk (distribution)
    std::vector<std::size_t> chunk_starts;
  };

  // Reads every input once through a three-stage pipeline: reading (serial: readers are not
  // thread-safe), `prepare` (parallel, per batch) and `apply` (serial, in input order), so that
  // parsing the next batch overlaps with the work on this one. `after_source`, if set, sees each
  // reader once its input is read.
  template <typename Prepare, typename Apply>
  void pipelinedPass(std::string_view phase, std::uint64_t total, Prepare&& prepare, Apply&& apply,
                     const std::function<void(const BuildSource&, const io::PointReader&)>& after_source = {}) {
    constexpr std::size_t kLiveBatches = 4;
    // The batches circulate instead of being allocated anew: their buffers keep their capacity.
    std::array<Batch, kLiveBatches> storage;
    std::vector<Batch*> free_batches;
    for (Batch& batch : storage) free_batches.push_back(&batch);
    std::mutex free_mutex;

    std::uint64_t done = 0;
    for (std::size_t s = 0; s < options_.sources.size(); ++s) {
      const BuildSource& source = options_.sources[s];
      const std::unique_ptr<io::PointReader> reader = source.open();
      tbb::parallel_pipeline(
          kLiveBatches,
          tbb::make_filter<void, Batch*>(tbb::filter_mode::serial_in_order, [&](tbb::flow_control& control) -> Batch* {
            Batch* batch = nullptr;
            {
              const std::lock_guard lock(free_mutex);
              batch = free_batches.back();
              free_batches.pop_back();
            }
            if (!reader->read(batch->points, kReadBatchPoints)) {
              const std::lock_guard lock(free_mutex);
              free_batches.push_back(batch);
              control.stop();
              return nullptr;
            }
            batch->source = s;
            return batch;
          }) & tbb::make_filter<Batch*, Batch*>(tbb::filter_mode::parallel, [&](Batch* batch) {
            prepare(*batch);
            return batch;
          }) & tbb::make_filter<Batch*, void>(tbb::filter_mode::serial_in_order, [&](Batch* batch) {
            apply(*batch);
            done += batch->points.size();
            if (options_.progress) options_.progress(phase, done, total);
            const std::lock_guard lock(free_mutex);
            free_batches.push_back(batch);
          }));
      if (after_source) after_source(source, *reader);
    }
  }

  void locateCells(Batch& batch) const {
    batch.cells.resize(batch.points.size());
    for (std::size_t i = 0; i < batch.points.size(); ++i) {
      const io::PointRecord& p = batch.points.points[i];
      batch.cells[i] = static_cast<std::uint32_t>(flatCell(header_.cube.cellAt({p.x, p.y, p.z}, kCountLevel)));
    }
  }

  // What a reader reports once its input is read: skipped points, attributes, ignored fields,
  // scans. Collected in the bounds pass only, which reads every input first.
  void collectInputFacts(const BuildSource& source, const io::PointReader& reader) {
    if (first_scan_.size() == options_.sources.size()) return;  // collected in an earlier pass
    header_.skipped_non_finite += reader.counts().non_finite;
    if (reader.info().attributes.colour) header_.attributes |= kHasColour;
    if (reader.info().attributes.intensity) header_.attributes |= kHasIntensity;
    for (const std::string& field : reader.info().ignored_fields)
      report_.ignored_fields.push_back(source.name + ": " + field);
    // Each input's scans follow the previous inputs' in the cloud's scan index, named by the
    // input's file name (its folder would only repeat).
    first_scan_.push_back(header_.scans.size());
    const std::string file = std::filesystem::path(source.name).filename().string();
    if (reader.info().scans.empty()) {
      header_.scans.push_back(file);
    } else {
      for (const std::string& scan : reader.info().scans) header_.scans.push_back(file + ": " + scan);
    }
  }

  // A cloud of several scans keeps each point's scan (kHasScanIndex); one of a single scan has
  // nothing to tell apart.
  void settleScans() {
    if (header_.scans.size() > std::size_t{std::numeric_limits<std::uint16_t>::max()} + 1) {
      throw Error("the inputs hold " + std::to_string(header_.scans.size()) +
                  " scans; an octree keeps at most 65536 (import them in parts)");
    }
    if (header_.scans.size() < 2) {
      header_.scans.clear();
      return;
    }
    header_.attributes |= kHasScanIndex;
    header_.scan_count = static_cast<std::uint32_t>(header_.scans.size());
  }

  static Box3 emptyBox() {
    Box3 box;
    box.min.fill(INFINITY);
    box.max.fill(-INFINITY);
    return box;
  }
  static void growBox(Box3& box, const Box3& other) {
    for (std::size_t a = 0; a < 3; ++a) {
      box.min[a] = std::min(box.min[a], other.min[a]);
      box.max[a] = std::max(box.max[a], other.max[a]);
    }
  }
  static void measureBatch(Batch& batch) {
    batch.box = emptyBox();
    for (const io::PointRecord& p : batch.points.points) {
      const double xyz[3] = {p.x, p.y, p.z};
      for (std::size_t a = 0; a < 3; ++a) {
        batch.box.min[a] = std::min(batch.box.min[a], xyz[a]);
        batch.box.max[a] = std::max(batch.box.max[a], xyz[a]);
      }
    }
  }

  // What every input's header states, read in one open of each: the union of their bounds and
  // the sum of their point counts (0 when one states none: the progress line then shows no
  // total). Nothing when one states no bounds, or none that are finite and ordered.
  std::optional<Declared> declaredByHeaders() const {
    Declared declared{emptyBox(), 0};
    bool every_count = true;
    for (const BuildSource& source : options_.sources) {
      const std::unique_ptr<io::PointReader> reader = source.open();
      const std::optional<io::Bounds>& bounds = reader->info().declared_bounds;
      if (!bounds) return std::nullopt;
      for (std::size_t a = 0; a < 3; ++a) {
        // Also refused: an extent too large for a double (bounds of +-1e308).
        if (!std::isfinite(bounds->max[a] - bounds->min[a]) || bounds->min[a] > bounds->max[a]) return std::nullopt;
      }
      growBox(declared.bounds, {bounds->min, bounds->max});
      const std::optional<std::uint64_t>& points = reader->info().declared_points;
      every_count = every_count && points.has_value();
      if (points) declared.points += *points;
    }
    if (!every_count) declared.points = 0;
    return declared;
  }

  void scanBounds() {
    header_.bounds = emptyBox();
    std::uint64_t count = 0;
    pipelinedPass(
        "reading bounds", 0, [](Batch& batch) { measureBatch(batch); },
        [&](const Batch& batch) {
          growBox(header_.bounds, batch.box);
          count += batch.points.size();
        },
        [&](const BuildSource& source, const io::PointReader& reader) { collectInputFacts(source, reader); });
    settleInputs(count);
    settleCube(header_.bounds);
  }

  // Once the first pass has read every input: the point count, the input files, the scans.
  void settleInputs(std::uint64_t count) {
    if (count == 0) throw noPointsError();
    header_.point_count = count;
    header_.input_files = static_cast<std::uint32_t>(options_.sources.size());
    settleScans();
  }

  // A build that found no points: the error names its inputs and counts the points it left out
  // for want of a position (an empty E57 or LAS, a PLY of NaNs).
  Error noPointsError() const {
    const std::vector<BuildSource>& sources = options_.sources;
    const std::uint64_t skipped = header_.skipped_non_finite;
    const std::string why = skipped > 0 ? " with a valid position (" + std::to_string(skipped) +
                                              " points without one were skipped)"
                                        : "";
    if (sources.size() == 1) return fileError(sources.front().name, "the file holds no points" + why);
    std::string names;
    for (const BuildSource& source : sources) names += (names.empty() ? "'" : ", '") + source.name + "'";
    return Error("none of the " + std::to_string(sources.size()) + " inputs holds a point" + why + ": " + names);
  }

  // The cube around `bounds`: a hair larger than them, so the farthest points stay inside.
  static Cube cubeAround(const Box3& bounds) {
    double extent = 0.0;
    for (std::size_t a = 0; a < 3; ++a) extent = std::max(extent, bounds.max[a] - bounds.min[a]);
    Cube cube;
    cube.size = extent > 0.0 ? extent * (1.0 + 1e-6) + 1e-6 : 1.0;
    for (std::size_t a = 0; a < 3; ++a) cube.origin[a] = 0.5 * (bounds.min[a] + bounds.max[a]) - 0.5 * cube.size;
    return cube;
  }

  void settleCube(const Box3& bounds) {
    header_.cube = cubeAround(bounds);
    header_.root_spacing = header_.cube.size / kSamplingGrid;
    header_.sampling_grid = kSamplingGrid;
    header_.leaf_max_points = options_.leaf_max_points;
  }

  // Whether the cube made from the headers' bounds serves the points the count measured: it holds
  // them, and it is within 1 % of the cube their own bounds give (headers round their bounds; a
  // loose header's larger cube would put the levels' spacings off the points').
  // The points must also lie inside the headers' bounds (but for rounding): the count's
  // histograms ran over them.
  bool declaredCubeHolds() const {
    const Cube own = cubeAround(header_.bounds);
    const double tolerance = 0.01 * own.size;
    const double rounding = 1e-6 * own.size;
    if (std::abs(own.size - header_.cube.size) > tolerance) return false;
    for (std::size_t a = 0; a < 3; ++a) {
      if (std::abs(own.origin[a] - header_.cube.origin[a]) > tolerance) return false;
      if (header_.bounds.min[a] < declared_->bounds.min[a] - rounding ||
          header_.bounds.max[a] > declared_->bounds.max[a] + rounding)
        return false;
    }
    return true;
  }

  // Counts the points per cell of the counting grid, and along each axis for the framing box.
  // The first pass to read the inputs when their headers gave the bounds: then it also measures
  // the points' bounds and count.
  std::vector<std::uint64_t> countCells() {
    const bool first_read = first_scan_.size() < options_.sources.size();
    std::vector<std::uint64_t> counts(kCountCells, 0);
    // Over the headers' bounds while the points' own are not known yet.
    AxisHistograms histograms(first_read ? declared_->bounds : header_.bounds);
    Box3 measured = emptyBox();
    std::uint64_t seen = 0;
    pipelinedPass(
        "counting", first_read ? declared_->points : header_.point_count,
        [&](Batch& batch) {
          locateCells(batch);
          if (!batch.histograms) batch.histograms.emplace(histograms.bounds());
          batch.histograms->clear();
          for (const io::PointRecord& p : batch.points.points) batch.histograms->add({p.x, p.y, p.z});
          if (first_read) measureBatch(batch);
        },
        [&](const Batch& batch) {
          for (std::uint32_t cell : batch.cells) ++counts[cell];
          histograms.merge(*batch.histograms);
          if (first_read) growBox(measured, batch.box);
          seen += batch.cells.size();
        },
        [&](const BuildSource& source, const io::PointReader& reader) { collectInputFacts(source, reader); });
    if (first_read) {
      settleInputs(seen);
      header_.bounds = measured;
    }
    // The inputs changed between passes, or a reader is not deterministic.
    if (seen != header_.point_count) throw Error("an input changed while it was being read; run the import again");
    // Inside the points' bounds, also where the histograms spanned the headers' wider ones.
    Box3 framing = histograms.framingBox();
    for (std::size_t a = 0; a < 3; ++a) {
      framing.min[a] = std::clamp(framing.min[a], header_.bounds.min[a], header_.bounds.max[a]);
      framing.max[a] = std::clamp(framing.max[a], framing.min[a], header_.bounds.max[a]);
    }
    header_.framing = framing;
    return counts;
  }

  // The largest chunk that threads can index side by side within the budget.
  std::uint64_t chunkLimit() const {
    const unsigned threads =
        options_.threads > 0 ? options_.threads : std::max(1u, std::thread::hardware_concurrency());
    const std::size_t per_thread = budget_bytes_ / threads;
    const std::size_t usable = per_thread > kIndexerScratchBytes ? per_thread - kIndexerScratchBytes : per_thread / 2;
    const std::uint64_t by_memory = usable / kIndexBytesPerPoint;
    // A chunk is indexed by one thread: about 16 chunks per thread keep every thread busy to the
    // end, whatever the sizes.
    const std::uint64_t by_balance = std::max<std::uint64_t>(header_.point_count / (16 * threads), kMinChunkPoints);
    return std::max<std::uint64_t>(std::min(by_memory, by_balance), 4 * std::uint64_t{options_.leaf_max_points});
  }

  void chooseChunks(const std::vector<std::uint64_t>& counts) {
    // Counts per level, from the counting grid up to the root.
    std::vector<std::vector<std::uint64_t>> pyramid(kCountLevel + 1);
    pyramid[kCountLevel] = counts;
    for (std::uint32_t level = kCountLevel; level > 0; --level) {
      pyramid[level - 1].assign(std::size_t{1} << (3 * (level - 1)), 0);
      const std::uint32_t n = 1u << level;
      for (std::uint32_t z = 0; z < n; ++z) {
        for (std::uint32_t y = 0; y < n; ++y) {
          for (std::uint32_t x = 0; x < n; ++x) {
            const CellKey key{level, x, y, z};
            pyramid[level - 1][flatCell(*key.parent())] += pyramid[level][flatCell(key)];
          }
        }
      }
    }
    const std::uint64_t limit = chunkLimit();
    chunk_of_cell_.assign(kCountCells, 0);
    std::vector<CellKey> pending{CellKey{}};
    while (!pending.empty()) {
      const CellKey key = pending.back();
      pending.pop_back();
      const std::uint64_t count = pyramid[key.level][flatCell(key)];
      if (count == 0) continue;
      if (count > limit && key.level < kCountLevel) {
        for (const CellKey& child : key.children()) pending.push_back(child);
        continue;
      }
      // Every counting cell inside this chunk maps to it.
      const std::uint32_t shift = kCountLevel - key.level;
      const std::uint32_t span = 1u << shift;
      for (std::uint32_t z = 0; z < span; ++z) {
        for (std::uint32_t y = 0; y < span; ++y) {
          for (std::uint32_t x = 0; x < span; ++x) {
            const CellKey cell{kCountLevel, (key.x << shift) + x, (key.y << shift) + y, (key.z << shift) + z};
            chunk_of_cell_[flatCell(cell)] = static_cast<std::uint32_t>(chunks_.size());
          }
        }
      }
      chunks_.push_back(std::make_unique<ChunkFile>(options_.output, key));
    }
  }

  void distribute() {
    // The parallel stage groups each batch by chunk, so the serial stage only appends runs.
    const std::size_t chunk_count = chunks_.size();
    pipelinedPass(
        "distributing", header_.point_count,
        [&](Batch& batch) {
          locateCells(batch);
          std::vector<std::size_t>& starts = batch.chunk_starts;
          starts.assign(chunk_count + 1, 0);
          for (std::uint32_t& cell : batch.cells) {
            cell = chunk_of_cell_[cell];  // from here on: the chunk of the point
            ++starts[cell + 1];
          }
          for (std::size_t c = 0; c < chunk_count; ++c) starts[c + 1] += starts[c];
          batch.by_chunk.resize(batch.cells.size());
          std::vector<std::size_t> next(starts.begin(), starts.end() - 1);
          const std::size_t first_scan = first_scan_[batch.source];
          for (std::size_t i = 0; i < batch.cells.size(); ++i) {
            const io::PointRecord& p = batch.points.points[i];
            const auto scan = static_cast<std::uint16_t>(header_.scan_count > 0 ? first_scan + p.scan : 0);
            const auto hash_high = static_cast<std::uint32_t>(thinningHash({p.x, p.y, p.z}) >> 32);
            batch.by_chunk[next[batch.cells[i]]++] = {
                placeOf(header_.cube, {p.x, p.y, p.z}), p.rgb, p.intensity, scan, 0, hash_high};
          }
        },
        [&](const Batch& batch) {
          for (std::size_t c = 0; c < chunk_count; ++c) {
            const std::size_t begin = batch.chunk_starts[c], end = batch.chunk_starts[c + 1];
            if (end > begin) chunks_[c]->append(std::span(batch.by_chunk).subspan(begin, end - begin));
          }
        });
    for (auto& chunk : chunks_) chunk->flush();
    chunk_of_cell_ = {};
  }

  // A counting cell denser than the chunk limit is split into its children by streaming its
  // file through, as often as needed.
  void splitOversizedChunks() {
    const std::uint64_t limit = chunkLimit();
    std::vector<std::unique_ptr<ChunkFile>> done;
    std::vector<BuildPoint> piece(kChunkBufferPoints * 16);
    while (!chunks_.empty()) {
      std::unique_ptr<ChunkFile> chunk = std::move(chunks_.back());
      chunks_.pop_back();
      if (chunk->count() <= limit || chunk->key().level >= kMaxLevel ||
          header_.cube.cellSize(chunk->key().level) < 1e-3) {
        done.push_back(std::move(chunk));
        continue;
      }
      std::array<std::unique_ptr<ChunkFile>, 8> children;
      for (int o = 0; o < 8; ++o)
        children[static_cast<std::size_t>(o)] = std::make_unique<ChunkFile>(options_.output, chunk->key().child(o));
      for (std::uint64_t first = 0; first < chunk->count(); first += piece.size()) {
        const auto n = static_cast<std::size_t>(std::min<std::uint64_t>(piece.size(), chunk->count() - first));
        chunk->read(first, std::span(piece).first(n));
        for (std::size_t i = 0; i < n; ++i) {
          children[static_cast<std::size_t>(octantOf(chunk->key(), piece[i].place))]->add(piece[i]);
        }
      }
      for (auto& child : children) {
        child->flush();
        if (child->count() > 0) chunks_.push_back(std::move(child));
      }
    }
    chunks_ = std::move(done);
    std::sort(chunks_.begin(), chunks_.end(), [](const auto& a, const auto& b) { return a->count() > b->count(); });
    for (const auto& chunk : chunks_) keys_.push_back(chunk->key());
    report_.chunks = chunks_.size();
    report_.largest_chunk_points = chunks_.empty() ? 0 : static_cast<std::size_t>(chunks_.front()->count());
  }

  void writeNode(const CellKey& key, std::span<const BuildPoint> points, std::uint8_t child_mask) {
    // Each point at the middle of its place's step, relative to the cell's minimum corner.
    const double step = std::ldexp(header_.cube.size, -32);
    const double cell_size = header_.cube.cellSize(key.level);
    const std::array<double, 3> corner{key.x * cell_size, key.y * cell_size, key.z * cell_size};
    const auto relative = [&](const BuildPoint& p, std::size_t a) {
      return static_cast<float>((p.place[a] + 0.5) * step - corner[a]);
    };
    std::vector<std::byte> block(nodeBlockBytes(points.size(), header_.attributes));
    for (std::size_t i = 0; i < points.size(); ++i) {
      const BuildPoint& p = points[i];
      encodePoint({relative(p, 0), relative(p, 1), relative(p, 2), p.rgb, p.intensity}, block.data() + i * kPointBytes);
    }
    if (header_.attributes & kHasScanIndex) {
      std::byte* scans = block.data() + points.size() * kPointBytes;
      for (std::size_t i = 0; i < points.size(); ++i)
        std::memcpy(scans + i * kScanIndexBytes, &points[i].scan, kScanIndexBytes);
    }
    NodeInfo node{key, static_cast<std::uint32_t>(points.size()), crc32Of(block), 0, child_mask};
    const std::lock_guard lock(output_mutex_);
    node.offset = output_->size();
    output_->write(block);
    nodes_.push_back(node);
    indexed_points_ += points.size();
    if (options_.progress) options_.progress("indexing", indexed_points_, header_.point_count);
  }

  void indexChunks() {
    const std::uint64_t largest = report_.largest_chunk_points;
    const std::size_t per_thread = largest * kIndexBytesPerPoint + kIndexerScratchBytes;
    const unsigned cores = options_.threads > 0 ? options_.threads : std::max(1u, std::thread::hardware_concurrency());
    const unsigned threads =
        static_cast<unsigned>(std::clamp<std::size_t>(budget_bytes_ / std::max<std::size_t>(per_thread, 1), 1, cores));
    report_.index_threads = threads;
    roots_.resize(chunks_.size());

    // One indexer (and its scratch) per worker thread of this build.
    tbb::enumerable_thread_specific<NodeIndexer> indexers(header_.cube, options_.leaf_max_points);
    tbb::task_arena arena(static_cast<int>(threads));
    arena.execute([&] {
      tbb::parallel_for(std::size_t{0}, chunks_.size(), [&](std::size_t c) {
        NodeIndexer& indexer = indexers.local();
        ChunkFile& chunk = *chunks_[c];
        std::vector<BuildPoint> points(static_cast<std::size_t>(chunk.count()));
        chunk.read(0, points);
        chunks_[c].reset();  // close the temporary file: its disk space is free from here on
        indexer.indexSubtree(keys_[c], points, {},
                             [&](const CellKey& key, std::span<const BuildPoint> node_points, std::uint8_t mask) {
                               if (key == keys_[c]) {
                                 roots_[c] = {std::vector<BuildPoint>(node_points.begin(), node_points.end()), mask};
                               } else {
                                 writeNode(key, node_points, mask);
                               }
                             });
      });
    });
  }

  void indexTopLevels() {
    if (keys_.size() == 1 && keys_[0].level == 0) {
      writeNode(keys_[0], roots_[0].points, roots_[0].child_mask);
      return;
    }
    std::unordered_map<CellKey, std::size_t, CellKeyHash> chunk_by_key;
    std::vector<BuildPoint> points;
    for (std::size_t c = 0; c < keys_.size(); ++c) {
      chunk_by_key.emplace(keys_[c], c);
      points.insert(points.end(), roots_[c].points.begin(), roots_[c].points.end());
      roots_[c].points = {};
    }
    const StopSet stops(keys_);
    NodeIndexer indexer(header_.cube, options_.leaf_max_points);
    indexer.indexAbove(
        CellKey{}, points, {}, stops,
        [&](const CellKey& key, std::span<const BuildPoint> remaining) {
          const std::uint8_t mask = roots_[chunk_by_key.at(key)].child_mask;
          if (remaining.empty() && mask == 0) return false;
          writeNode(key, remaining, mask);
          return true;
        },
        [&](const CellKey& key, std::span<const BuildPoint> node_points, std::uint8_t mask) {
          writeNode(key, node_points, mask);
        });
  }

  void finish(AtomicFile& output) {
    if (indexed_points_ != header_.point_count) {
      throw Error("internal error: indexed " + std::to_string(indexed_points_) + " of " +
                  std::to_string(header_.point_count) + " points");
    }
    std::sort(nodes_.begin(), nodes_.end(), [](const NodeInfo& a, const NodeInfo& b) {
      return std::tie(a.key.level, a.key.z, a.key.y, a.key.x) < std::tie(b.key.level, b.key.z, b.key.y, b.key.x);
    });
    std::vector<std::byte> index(nodes_.size() * kIndexEntryBytes);
    for (std::size_t i = 0; i < nodes_.size(); ++i) {
      encodeIndexEntry(nodes_[i], index.data() + i * kIndexEntryBytes);
      header_.depth = std::max(header_.depth, nodes_[i].key.level);
    }
    header_.node_count = nodes_.size();
    header_.index_offset = output.size();
    header_.index_bytes = index.size();
    header_.index_crc = crc32Of(index);
    output.write(index);
    if (header_.scan_count > 0) {
      const std::vector<std::byte> table = encodeScanTable(header_.scans);
      header_.scan_table_offset = output.size();
      header_.scan_table_bytes = table.size();
      header_.scan_table_crc = crc32Of(table);
      output.write(table);
    }
    output.overwrite(0, encodeHeader(header_));
    output.commit();

    report_.points = header_.point_count;
    report_.skipped_non_finite = header_.skipped_non_finite;
    report_.nodes = nodes_.size();
    report_.depth = header_.depth;
    report_.file_bytes = output.size();
    report_.scans = header_.scans;
  }

  struct ChunkRoot {
    std::vector<BuildPoint> points;
    std::uint8_t child_mask = 0;
  };

  const BuildOptions& options_;
  std::size_t budget_bytes_ = 0;
  OctreeHeader header_;
  BuildReport report_;
  std::vector<std::uint32_t> chunk_of_cell_;
  std::vector<std::unique_ptr<ChunkFile>> chunks_;
  std::vector<CellKey> keys_;  // of each chunk, kept after its file is closed
  std::vector<ChunkRoot> roots_;
  AtomicFile* output_ = nullptr;
  std::mutex output_mutex_;
  std::vector<NodeInfo> nodes_;
  std::uint64_t indexed_points_ = 0;
  std::vector<std::size_t> first_scan_;  // per input: the index of its first scan
  std::optional<Declared> declared_;     // what the inputs' headers state, if every one states bounds
};

}  // namespace

std::vector<BuildSource> fileSources(const std::vector<std::string>& paths, const io::ReaderOptions& options) {
  std::vector<BuildSource> sources;
  for (const std::string& path : paths) {
    sources.push_back({path, [path, options] { return io::openPointCloud(path, options); }});
  }
  return sources;
}

BuildReport buildOctree(const BuildOptions& options) {
  return Builder(options).run();
}

}  // namespace plumb::lod
