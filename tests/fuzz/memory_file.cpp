#include "tests/fuzz/memory_file.h"

#include <sys/mman.h>
#include <unistd.h>

namespace plumb::fuzz {

std::string memoryFile(const std::uint8_t* data, std::size_t size) {
  static const int fd = ::memfd_create("plumb-fuzz", 0);
  if (fd < 0 || ::ftruncate(fd, 0) != 0) __builtin_trap();
  std::size_t done = 0;
  while (done < size) {
    const ssize_t written = ::pwrite(fd, data + done, size - done, static_cast<off_t>(done));
    if (written <= 0) __builtin_trap();
    done += static_cast<std::size_t>(written);
  }
  return "/proc/self/fd/" + std::to_string(fd);
}

}  // namespace plumb::fuzz
