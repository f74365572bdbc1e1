// libFuzzer target for the point-cloud readers; PLUMB_FUZZ_READER (a compile definition) picks
// the reader: ply, las, pcd, e57 or ascii. Any input must end in points or a plumb::Error, never in
// a crash, a hang or a sanitizer report. Run by scripts/fuzz.

#include <sys/mman.h>
#include <unistd.h>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>

#include "engine/core/error.h"
#include "engine/io/point_reader.h"

namespace {

// The readers take paths: hand them an in-memory file.
std::string memoryFile(const std::uint8_t* data, std::size_t size) {
  static const int fd = ::memfd_create("plumb-fuzz", 0);
  if (::ftruncate(fd, 0) != 0) __builtin_trap();
  std::size_t done = 0;
  while (done < size) {
    const ssize_t written = ::pwrite(fd, data + done, size - done, static_cast<off_t>(done));
    if (written <= 0) __builtin_trap();
    done += static_cast<std::size_t>(written);
  }
  return "/proc/self/fd/" + std::to_string(fd);
}

std::unique_ptr<plumb::io::PointReader> open(const std::string& path) {
  const std::string reader = PLUMB_FUZZ_READER;
  if (reader == "ply") return plumb::io::openPly(path);
  if (reader == "las") return plumb::io::openLas(path);
  if (reader == "pcd") return plumb::io::openPcd(path);
  if (reader == "e57") return plumb::io::openE57(path);
  return plumb::io::openAscii(path, {});
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    const auto reader = open(memoryFile(data, size));
    plumb::io::PointBatch batch;
    while (reader->read(batch, 1000)) {
      for (const auto& p : batch.points) {
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) __builtin_trap();
      }
    }
  } catch (const plumb::Error&) {
    // Malformed input, reported: what the reader must do.
  }
  return 0;
}
