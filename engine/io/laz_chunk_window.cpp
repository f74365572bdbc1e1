#include "engine/io/laz_chunk_window.h"

#include <tbb/task_group.h>

#include <algorithm>
#include <cassert>
#include <cstring>
#include <utility>

#include "engine/core/tsan_handover.h"
#include "engine/io/file_source.h"
#include "engine/io/laz_point_decompressor.h"

namespace plumb::io {

struct LazChunkWindow::Tasks {
  tbb::task_group group;
};

// A named task rather than a lambda, so that ThreadSanitizer's suppressions can name the read of
// its member, which oneTBB hands over unseen (tests/engine/jobs/tsan.supp).
struct LazChunkWindow::RunQueuedTask {
  LazChunkWindow* window;
  void operator()() const {
    PLUMB_TSAN_ACQUIRE(window);
    window->runQueued();
  }
};

LazChunkWindow::LazChunkWindow(std::string path, const LaszipVlr& vlr, LazChunkTable table, std::size_t record_length,
                               std::size_t chunks_in_flight)
    : path_(std::move(path)),
      vlr_(vlr),
      table_(std::move(table)),
      record_length_(record_length),
      chunks_in_flight_(chunks_in_flight),
      tasks_(std::make_unique<Tasks>()) {
  assert(table_.present && chunks_in_flight_ >= 1 && "a window over the chunk table's chunks");
}

LazChunkWindow::~LazChunkWindow() {
  {
    const std::lock_guard lock(mutex_);
    stopping_ = true;
  }
  // Tasks not yet started return at once; running ones finish their chunk.
  tasks_->group.wait();
}

std::size_t LazChunkWindow::chunkBytes(std::size_t index) const {
  return static_cast<std::size_t>(table_.chunks[index].points) * record_length_;
}

std::size_t LazChunkWindow::heldBytes(std::size_t index) const {
  // A chunk takes the spare buffer, which may be larger than it needs.
  return std::max(chunkBytes(index), spare_.capacity());
}

void LazChunkWindow::fillLocked() {
  while (next_chunk_ < table_.chunks.size() && window_.size() < chunks_in_flight_ &&
         (window_.empty() || window_bytes_ + heldBytes(next_chunk_) <= kWindowBytes)) {
    Chunk& chunk = window_.emplace_back();
    chunk.index = next_chunk_++;
    chunk.held = heldBytes(chunk.index);
    chunk.records = std::move(spare_);
    spare_ = {};
    window_bytes_ += chunk.held;
    // The task takes the oldest queued chunk when it runs, not this one: the chunk travels under
    // the mutex (which ThreadSanitizer sees), and the caller may have decoded it meanwhile.
    PLUMB_TSAN_RELEASE(this);
    tasks_->group.run(RunQueuedTask{this});
  }
}

void LazChunkWindow::runQueued() {
  Chunk* chunk = nullptr;
  {
    const std::lock_guard lock(mutex_);
    if (stopping_) return;
    const auto queued =
        std::find_if(window_.begin(), window_.end(), [](const Chunk& c) { return c.state == State::queued; });
    if (queued == window_.end()) return;
    chunk = &*queued;
    chunk->state = State::running;
  }
  decodeChunk(*chunk);
  {
    const std::lock_guard lock(mutex_);
    chunk->state = State::done;
  }
  done_.notify_all();
}

void LazChunkWindow::decodeChunk(Chunk& chunk) const {
  const LazChunk& listed = table_.chunks[chunk.index];
  std::unique_ptr<LazPointDecompressor> decompressor;
  try {
    chunk.records.resize(chunkBytes(chunk.index));
    // Its own file handle: FileSource is not thread-safe, and a chunk is read in one stretch.
    FileSource source(path_);
    LazChunkTable alone;
    alone.present = true;
    alone.chunks_start = listed.offset;
    alone.chunks = {listed};
    decompressor = std::make_unique<LazPointDecompressor>(source, vlr_, std::move(alone), record_length_, chunk.index,
                                                          table_.chunks.size());
    decompressor->decode(chunk.records);
    chunk.good = static_cast<std::size_t>(listed.points);
  } catch (...) {
    chunk.good = decompressor ? static_cast<std::size_t>(decompressor->decoded()) : 0;
    chunk.error = std::current_exception();
  }
}

LazChunkWindow::Chunk& LazChunkWindow::oldestDecoded() {
  std::unique_lock lock(mutex_);
  fillLocked();
  assert(!window_.empty() && "decode() past the declared points");
  Chunk& oldest = window_.front();
  // Until the oldest is decoded, decode here what no worker has taken yet: the oldest itself, or,
  // while a worker is on it, the next chunk queued. Waiting instead kept the two threads of a
  // two-core machine taking turns: the worker took each chunk first and the caller waited for it.
  while (oldest.state != State::done) {
    const auto queued =
        std::find_if(window_.begin(), window_.end(), [](const Chunk& c) { return c.state == State::queued; });
    if (queued == window_.end()) {
      done_.wait(lock, [&] { return oldest.state == State::done; });
      break;
    }
    Chunk& chunk = *queued;
    chunk.state = State::running;
    lock.unlock();
    decodeChunk(chunk);
    lock.lock();
    chunk.state = State::done;
  }
  return oldest;
}

void LazChunkWindow::decode(std::span<std::byte> records) {
  const std::size_t count = records.size() / record_length_;
  std::size_t out = 0;
  while (out < count) {
    Chunk& chunk = oldestDecoded();
    const std::size_t take = std::min(count - out, chunk.good - chunk.handed);
    std::memcpy(records.data() + out * record_length_, chunk.records.data() + chunk.handed * record_length_,
                take * record_length_);
    chunk.handed += take;
    out += take;
    if (chunk.handed < chunk.good) continue;
    // Asked for the record that failed: its error, now and on every later call.
    if (out < count && chunk.error) std::rethrow_exception(chunk.error);
    if (chunk.error) continue;
    const std::lock_guard lock(mutex_);
    window_bytes_ -= chunk.held;
    spare_ = std::move(chunk.records);
    window_.pop_front();
  }
}

}  // namespace plumb::io
