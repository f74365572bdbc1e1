#pragma once
// A file that appears at its final path only once it is complete.
//
// Writes go to a temporary file beside the target ("<path>.partial-<pid>-<n>"); finish() flushes
// and fsyncs it, commit() renames it over the target and fsyncs the directory. An AtomicFile
// destroyed before commit(), or a process stopped by SIGINT, SIGTERM or SIGHUP, removes the
// temporary file, so an interrupted or failed command leaves no partial output behind. What a
// process stopped by SIGKILL leaves goes when the next AtomicFile of the same path is made.
// Commands with several outputs finish() all of them before they commit() any.
//
// Not thread-safe: one thread writes one AtomicFile.

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace plumb {

// Removes the temporary files of `target` that a process stopped by SIGKILL (or a power cut)
// left behind: "<target>.partial-<pid>-<n>" whose process no longer runs. A process still running
// (this one, or one of another user: kill answers EPERM) keeps its file. Never throws.
void removeAbandonedTemporaries(const std::string& target);

class AtomicFile {
 public:
  // Creates the temporary file. Throws plumb::Error naming `path` when it cannot.
  explicit AtomicFile(std::string path);
  ~AtomicFile();
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  // Appends bytes (buffered). Throws plumb::Error on a write failure such as a full disk.
  void write(std::span<const std::byte> bytes);
  void write(const void* data, std::size_t size);

  // Overwrites already written bytes at `offset` (used to patch headers with final counts).
  // The range must lie within what was written so far.
  void overwrite(std::uint64_t offset, std::span<const std::byte> bytes);

  // Bytes written so far.
  std::uint64_t size() const { return size_; }

  // Flushes and fsyncs the temporary file; no more writes afterwards.
  void finish();

  // Renames the finished temporary file over `path`. Calls finish() if needed.
  void commit();

  const std::string& path() const { return path_; }

 private:
  void flushBuffer();
  void discard() noexcept;

  std::string path_;
  std::string temp_path_;
  int fd_ = -1;
  int cleanup_slot_ = -1;
  std::vector<std::byte> buffer_;
  std::uint64_t size_ = 0;
  bool finished_ = false;
  bool committed_ = false;
};

}  // namespace plumb
