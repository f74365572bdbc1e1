#include "engine/core/atomic_file.h"

#include <fcntl.h>
#include <signal.h>
#include <unistd.h>

#include <atomic>
#include <cassert>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <mutex>

#include "engine/core/error.h"

namespace plumb {
namespace {

constexpr std::size_t kBufferBytes = std::size_t{1} << 20;

// Temporary files that a fatal signal must remove. A signal handler may only call
// async-signal-safe functions, so the registry is a fixed table of plain character arrays
// guarded by atomic states instead of a std::vector behind a mutex.
constexpr int kCleanupSlots = 16;
constexpr std::size_t kCleanupPathBytes = 4096;
enum SlotState : int { kSlotFree = 0, kSlotClaimed = 1, kSlotLive = 2 };
std::atomic<int> g_slot_state[kCleanupSlots];
char g_slot_path[kCleanupSlots][kCleanupPathBytes];

extern "C" void removeTemporariesAndDie(int signal_number) {
  for (int i = 0; i < kCleanupSlots; ++i) {
    if (g_slot_state[i].load() == kSlotLive) ::unlink(g_slot_path[i]);
  }
  ::signal(signal_number, SIG_DFL);
  ::raise(signal_number);
}

void installCleanupHandlersOnce() {
  static std::once_flag once;
  std::call_once(once, [] {
    for (int signal_number : {SIGINT, SIGTERM, SIGHUP}) {
      struct sigaction current {};
      // Leave handlers that the application installed itself alone.
      if (::sigaction(signal_number, nullptr, &current) == 0 && current.sa_handler == SIG_DFL) {
        struct sigaction action {};
        action.sa_handler = removeTemporariesAndDie;
        sigemptyset(&action.sa_mask);
        ::sigaction(signal_number, &action, nullptr);
      }
    }
  });
}

// Returns the claimed slot, or -1 when the table is full or the path too long: the file then
// still appears atomically, it is only not removed on a signal.
int registerForCleanup(const std::string& temp_path) {
  installCleanupHandlersOnce();
  if (temp_path.size() >= kCleanupPathBytes) return -1;
  for (int i = 0; i < kCleanupSlots; ++i) {
    int expected = kSlotFree;
    if (g_slot_state[i].compare_exchange_strong(expected, kSlotClaimed)) {
      std::memcpy(g_slot_path[i], temp_path.c_str(), temp_path.size() + 1);
      g_slot_state[i].store(kSlotLive);
      return i;
    }
  }
  return -1;
}

void unregisterForCleanup(int slot) {
  if (slot >= 0) g_slot_state[slot].store(kSlotFree);
}

std::string makeTempPath(const std::string& path) {
  static std::atomic<unsigned> counter{0};
  return path + ".partial-" + std::to_string(::getpid()) + "-" + std::to_string(counter.fetch_add(1));
}

}  // namespace

void removeAbandonedTemporaries(const std::string& target_path) {
  namespace fs = std::filesystem;
  const fs::path target(target_path);
  const std::string prefix = target.filename().string() + ".partial-";
  const fs::path folder = target.has_parent_path() ? target.parent_path() : fs::path(".");
  std::error_code error;
  for (fs::directory_iterator it(folder, error), end; !error && it != end; it.increment(error)) {
    const std::string name = it->path().filename().string();
    if (name.compare(0, prefix.size(), prefix) != 0) continue;
    const std::string rest = name.substr(prefix.size());
    const std::size_t dash = rest.find('-');
    if (dash == 0 || dash == std::string::npos || rest.find_first_not_of("0123456789-") != std::string::npos) continue;
    const long pid = std::strtol(rest.substr(0, dash).c_str(), nullptr, 10);
    if (pid <= 0 || pid == ::getpid()) continue;
    if (::kill(static_cast<pid_t>(pid), 0) != 0 && errno == ESRCH) {
      std::error_code ignored;
      fs::remove(it->path(), ignored);
    }
  }
}

AtomicFile::AtomicFile(std::string path) : path_(std::move(path)), temp_path_(makeTempPath(path_)) {
  const std::filesystem::path target(path_);
  if (target.filename().empty()) throw fileError(path_, "is a directory name, not a file name");
  std::error_code error;
  if (std::filesystem::is_directory(target, error)) throw fileError(path_, "is a directory");
  removeAbandonedTemporaries(path_);

  cleanup_slot_ = registerForCleanup(temp_path_);
  fd_ = ::open(temp_path_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
  if (fd_ < 0) {
    const int open_error = errno;
    unregisterForCleanup(cleanup_slot_);
    throw fileError(path_, "cannot create the output (" + systemErrorText(open_error) +
                               "); check that the folder exists and is writable");
  }
  buffer_.reserve(kBufferBytes);
}

AtomicFile::~AtomicFile() {
  if (!committed_) discard();
}

void AtomicFile::discard() noexcept {
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
  ::unlink(temp_path_.c_str());
  unregisterForCleanup(cleanup_slot_);
  cleanup_slot_ = -1;
}

void AtomicFile::write(const void* data, std::size_t size) {
  write(std::span<const std::byte>(static_cast<const std::byte*>(data), size));
}

void AtomicFile::write(std::span<const std::byte> bytes) {
  assert(!finished_ && "AtomicFile::write after finish(): write everything first");
  if (buffer_.size() + bytes.size() > kBufferBytes) flushBuffer();
  if (bytes.size() >= kBufferBytes) {
    // Large blocks bypass the buffer: one copy less for bulk point data.
    buffer_.assign(bytes.begin(), bytes.end());
    flushBuffer();
  } else {
    buffer_.insert(buffer_.end(), bytes.begin(), bytes.end());
  }
  size_ += bytes.size();
}

void AtomicFile::flushBuffer() {
  const std::byte* data = buffer_.data();
  std::size_t left = buffer_.size();
  while (left > 0) {
    const ssize_t written = ::write(fd_, data, left);
    if (written < 0) {
      if (errno == EINTR) continue;
      throw fileError(path_, "write failed (" + systemErrorText(errno) + ")");
    }
    data += written;
    left -= static_cast<std::size_t>(written);
  }
  buffer_.clear();
}

void AtomicFile::overwrite(std::uint64_t offset, std::span<const std::byte> bytes) {
  assert(offset + bytes.size() <= size_ && "AtomicFile::overwrite beyond the written size");
  assert(!finished_ && "AtomicFile::overwrite after finish()");
  flushBuffer();
  std::size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t written = ::pwrite(fd_, bytes.data() + done, bytes.size() - done, static_cast<off_t>(offset + done));
    if (written < 0) {
      if (errno == EINTR) continue;
      throw fileError(path_, "write failed (" + systemErrorText(errno) + ")");
    }
    done += static_cast<std::size_t>(written);
  }
}

void AtomicFile::finish() {
  if (finished_) return;
  flushBuffer();
  if (::fsync(fd_) != 0) throw fileError(path_, "cannot flush to disk (" + systemErrorText(errno) + ")");
  if (::close(fd_) != 0) {
    fd_ = -1;
    throw fileError(path_, "cannot close (" + systemErrorText(errno) + ")");
  }
  fd_ = -1;
  finished_ = true;
}

void AtomicFile::commit() {
  assert(!committed_ && "AtomicFile::commit called twice");
  finish();
  if (::rename(temp_path_.c_str(), path_.c_str()) != 0) {
    throw fileError(path_, "cannot move the finished output into place (" + systemErrorText(errno) + ")");
  }
  committed_ = true;
  unregisterForCleanup(cleanup_slot_);
  cleanup_slot_ = -1;

  // The rename is durable only once the directory entry is on disk too.
  std::filesystem::path directory = std::filesystem::path(path_).parent_path();
  if (directory.empty()) directory = ".";
  const int directory_fd = ::open(directory.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (directory_fd >= 0) {
    ::fsync(directory_fd);
    ::close(directory_fd);
  }
}

}  // namespace plumb
