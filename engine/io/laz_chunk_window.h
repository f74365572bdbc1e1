#pragma once
// The point data of a chunked LAZ file decoded a few chunks ahead, in parallel, and handed out in
// file order. LASzip compresses the points in chunks so that they can be reached without decoding
// what comes before (Isenburg 2013, "LASzip: lossless compression of LiDAR data", PE&RS 79(2)):
// each chunk starts with its first point raw, a fresh arithmetic decoder and fresh models, and the
// chunk table gives where each one starts and, for variable chunks, how many points it holds
// (laz_chunk_table.h; the reference implementation, src/lasreadpoint.cpp). So chunk k decoded on its own
// (LazPointDecompressor over that chunk alone) gives exactly the records the sequential decoder
// gives for it, and the records, the errors and where they surface are those of the sequential
// decoder, whatever the threads or the load.
//
//   1. A window of the next chunks, at most `chunks_in_flight` of them and kWindowBytes of decoded
//      records (at least one chunk), each queued as a oneTBB task in the calling thread's arena.
//      A task decodes its chunk through its own FileSource into the chunk's own buffer.
//   2. decode() copies the records out of the oldest chunk; when that chunk is still queued, the
//      calling thread decodes it itself (so progress never depends on a free worker), and when a
//      worker is on it, decodes the next queued chunk meanwhile, waiting only when none is left
//      (else the two threads of two cores take turns). An emptied chunk leaves the window and the
//      next one enters.
//   3. A chunk that fails keeps the records decoded before the failure and the exception: decode()
//      hands those out, then throws the exception exactly where the sequential decoder would (on
//      the call that asks for the record that failed), never before the records of earlier chunks.
//
// Memory: chunk buffers of at most kWindowBytes (64 MiB) in the window, or one chunk's when a chunk
// is larger (callers keep chunks above kMaxChunkBytes sequential), plus the buffer of the chunk
// that left last, kept for the next to enter (no larger than the largest chunk), plus each chunk's
// models and a 64 KiB read buffer while it is decoded. Not thread-safe: one thread calls decode(); the tasks only touch
// their own chunk, and hand it back under the mutex. The destructor waits for running tasks.

#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <exception>
#include <memory>
#include <mutex>
#include <span>
#include <string>
#include <vector>

#include "engine/io/laszip_vlr.h"
#include "engine/io/laz_chunk_table.h"

namespace plumb::io {

class LazChunkWindow {
 public:
  // Decoded records in flight, over all chunks of the window.
  static constexpr std::size_t kWindowBytes = std::size_t{64} << 20;
  // Chunks whose records exceed this are best decoded sequentially (streaming, no chunk buffer).
  static constexpr std::size_t kMaxChunkBytes = std::size_t{16} << 20;

  // `table`: present, of the file at `path`, whose laszip VLR is `vlr` (compressor 2 or 3), with
  // records of `record_length` bytes. `chunks_in_flight` >= 1.
  LazChunkWindow(std::string path, const LaszipVlr& vlr, LazChunkTable table, std::size_t record_length,
                 std::size_t chunks_in_flight);
  ~LazChunkWindow();
  LazChunkWindow(const LazChunkWindow&) = delete;
  LazChunkWindow& operator=(const LazChunkWindow&) = delete;

  // As LazPointDecompressor::decode: the next records.size() / record_length records (no more
  // than remain). Throws the plumb::Error the sequential decoder would throw, at the same record.
  void decode(std::span<std::byte> records);

 private:
  enum class State { queued, running, done };
  struct Chunk {
    std::size_t index = 0;  // in the table
    State state = State::queued;
    std::vector<std::byte> records;
    std::size_t good = 0;      // records decoded whole (all of them unless `error`)
    std::size_t handed = 0;    // records decode() has copied out
    std::size_t held = 0;      // bytes of its buffer, counted against kWindowBytes
    std::exception_ptr error;  // the decoder's failure after `good` records
  };
  struct Tasks;  // the oneTBB task group, kept out of this header
  struct RunQueuedTask;

  void fillLocked();
  Chunk& oldestDecoded();
  void runQueued();
  void decodeChunk(Chunk& chunk) const;
  std::size_t chunkBytes(std::size_t index) const;
  std::size_t heldBytes(std::size_t index) const;

  const std::string path_;
  const LaszipVlr vlr_;
  const LazChunkTable table_;
  const std::size_t record_length_;
  const std::size_t chunks_in_flight_;

  std::mutex mutex_;              // guards the chunks' states and the deque, stopping_
  std::condition_variable done_;  // a chunk became done
  std::deque<Chunk> window_;      // in file order; references stay valid while a chunk is in it
  std::size_t next_chunk_ = 0;    // the next to enter the window
  std::size_t window_bytes_ = 0;  // the chunks' buffers in the window (Chunk::held)
  bool stopping_ = false;         // the destructor runs: queued tasks do nothing
  std::vector<std::byte> spare_;  // the buffer of the chunk that left last, for the next to enter
  std::unique_ptr<Tasks> tasks_;
};

}  // namespace plumb::io
