#include "engine/io/file_source.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>

namespace plumb::io {
namespace {

constexpr std::size_t kBufferBytes = std::size_t{4} << 20;

}  // namespace

FileSource::FileSource(std::string path) : path_(std::move(path)) {
  fd_ = ::open(path_.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd_ < 0) throw fileError(path_, "cannot open (" + systemErrorText(errno) + ")");
  struct stat status {};
  if (::fstat(fd_, &status) != 0 || !S_ISREG(status.st_mode)) {
    ::close(fd_);
    throw fileError(path_, "is not a regular file");
  }
  size_ = static_cast<std::uint64_t>(status.st_size);
  ::posix_fadvise(fd_, 0, 0, POSIX_FADV_SEQUENTIAL);
  // Small files get a small buffer: tests and headers should not cost 4 MB each.
  buffer_.resize(static_cast<std::size_t>(std::clamp<std::uint64_t>(size_, 1, kBufferBytes)));
}

FileSource::~FileSource() {
  if (fd_ >= 0) ::close(fd_);
}

// Makes the buffer hold the bytes at offset_; false at the end of the file.
bool FileSource::fill() {
  if (offset_ >= buffer_start_ && offset_ < buffer_start_ + buffer_fill_) return true;
  if (offset_ >= size_) return false;
  buffer_start_ = offset_;
  buffer_fill_ = 0;
  while (buffer_fill_ < buffer_.size()) {
    const ssize_t got = ::pread(fd_, buffer_.data() + buffer_fill_, buffer_.size() - buffer_fill_,
                                static_cast<off_t>(buffer_start_ + buffer_fill_));
    if (got < 0) {
      if (errno == EINTR) continue;
      throw errorHere("read failed (" + systemErrorText(errno) + ")");
    }
    if (got == 0) break;
    buffer_fill_ += static_cast<std::size_t>(got);
  }
  return buffer_fill_ > 0;
}

std::size_t FileSource::readSome(std::span<std::byte> bytes) {
  std::size_t done = 0;
  while (done < bytes.size() && fill()) {
    const std::size_t at = static_cast<std::size_t>(offset_ - buffer_start_);
    const std::size_t take = std::min(bytes.size() - done, buffer_fill_ - at);
    std::memcpy(bytes.data() + done, buffer_.data() + at, take);
    done += take;
    offset_ += take;
  }
  return done;
}

void FileSource::readExactly(std::span<std::byte> bytes, std::string_view what) {
  const std::uint64_t start = offset_;
  if (readSome(bytes) != bytes.size()) {
    throw errorAt(start, "truncated: the file ends in the middle of " + std::string(what) + " (needs " +
                             std::to_string(bytes.size()) + " bytes, " + std::to_string(size_ - start) + " left)");
  }
}

bool FileSource::readLine(std::string& line, std::size_t max_line_bytes) {
  line.clear();
  if (!fill()) return false;
  ++line_number_;
  while (fill()) {
    const std::size_t at = static_cast<std::size_t>(offset_ - buffer_start_);
    const std::byte* begin = buffer_.data() + at;
    const std::byte* end = buffer_.data() + buffer_fill_;
    const std::byte* newline = std::find(begin, end, std::byte{'\n'});
    line.append(reinterpret_cast<const char*>(begin), static_cast<std::size_t>(newline - begin));
    offset_ += static_cast<std::uint64_t>(newline - begin);
    if (line.size() > max_line_bytes)
      throw errorAtLine("line longer than " + std::to_string(max_line_bytes) + " bytes");
    if (newline != end) {
      ++offset_;  // the newline itself
      break;
    }
  }
  if (!line.empty() && line.back() == '\r') line.pop_back();
  return true;
}

void FileSource::seek(std::uint64_t offset) {
  offset_ = std::min(offset, size_);
}

void FileSource::skip(std::uint64_t bytes, std::string_view what) {
  if (bytes > remaining()) {
    throw errorHere("truncated: the file ends in the middle of " + std::string(what) + " (needs " +
                    std::to_string(bytes) + " bytes, " + std::to_string(remaining()) + " left)");
  }
  offset_ += bytes;
}

Error FileSource::errorAtLine(std::string_view what) const {
  return Error("'" + path_ + "' line " + std::to_string(line_number_) + ": " + std::string(what));
}

}  // namespace plumb::io
