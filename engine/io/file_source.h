#pragma once
// Buffered, streaming reading of a file with the byte offset always known, so that every reader
// can say where a file goes wrong. Reads in blocks (never the whole file); not thread-safe.

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "engine/core/error.h"

namespace plumb::io {

class FileSource {
 public:
  // Opens `path` for reading. Throws plumb::Error naming the file when it cannot.
  explicit FileSource(std::string path);
  ~FileSource();
  FileSource(const FileSource&) = delete;
  FileSource& operator=(const FileSource&) = delete;

  const std::string& path() const { return path_; }
  std::uint64_t size() const { return size_; }
  // Offset of the next byte read() or readLine() returns.
  std::uint64_t offset() const { return offset_; }
  std::uint64_t remaining() const { return size_ - offset_; }
  bool atEnd() const { return offset_ >= size_; }

  // Exactly `bytes.size()` bytes; throws "truncated" naming the offset and `what` when the file
  // ends first.
  void readExactly(std::span<std::byte> bytes, std::string_view what);
  // Up to `bytes.size()` bytes; returns how many were read (0 at the end).
  std::size_t readSome(std::span<std::byte> bytes);

  // The next line without its "\n" (and "\r"), or false at the end of the file. Lines longer
  // than `max_line_bytes` are an error (a binary file read as text, say).
  bool readLine(std::string& line, std::size_t max_line_bytes = 1 << 20);
  // 1-based number of the line readLine() returned last.
  std::uint64_t lineNumber() const { return line_number_; }

  // Moves to an absolute offset (<= size()).
  void seek(std::uint64_t offset);
  void skip(std::uint64_t bytes, std::string_view what);

  // "<path> at byte <offset>: <what>" at the current offset, or at `offset`.
  Error errorHere(std::string_view what) const { return fileErrorAt(path_, offset_, what); }
  Error errorAt(std::uint64_t offset, std::string_view what) const { return fileErrorAt(path_, offset, what); }
  // "<path> line <n>: <what>" for text formats.
  Error errorAtLine(std::string_view what) const;

 private:
  bool fill();

  std::string path_;
  int fd_ = -1;
  std::uint64_t size_ = 0;
  std::uint64_t offset_ = 0;  // logical position
  std::vector<std::byte> buffer_;
  std::uint64_t buffer_start_ = 0;  // file offset of buffer_[0]
  std::size_t buffer_fill_ = 0;     // valid bytes in buffer_
  std::uint64_t line_number_ = 0;
};

}  // namespace plumb::io
