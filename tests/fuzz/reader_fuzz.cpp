// libFuzzer target for the point-cloud readers; PLUMB_FUZZ_READER (a compile definition) picks
// the reader: ply, las (LAS, LAZ and COPC), pcd, e57 or ascii. Any input must end in points or a
// plumb::Error, never in a crash, a hang or a sanitizer report. Run by scripts/fuzz, and replayed
// in the test suite (fuzz_replay_main.cpp).

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "engine/core/error.h"
#include "engine/io/crc32c.h"
#include "engine/io/point_reader.h"
#include "tests/fuzz/memory_file.h"

namespace {

std::unique_ptr<plumb::io::PointReader> open(const std::string& path) {
  const std::string reader = PLUMB_FUZZ_READER;
  if (reader == "ply") return plumb::io::openPly(path);
  if (reader == "las") return plumb::io::openLas(path);
  if (reader == "pcd") return plumb::io::openPcd(path);
  if (reader == "e57") return plumb::io::openE57(path);
  return plumb::io::openAscii(path, {});
}

// E57 pages end in a big-endian CRC-32C of their first 1020 bytes. Fuzz builds do not check them
// (FUZZING_BUILD_MODE_UNSAFE_FOR_PRODUCTION, CMakeLists.txt), other builds do: repair them, so
// that the replay in the test suite (a GCC build) reaches the decoders too.
void repairE57Checksums(std::vector<std::uint8_t>& bytes) {
  constexpr std::size_t kPage = 1024, kData = 1020;
  for (std::size_t page = 0; page + kPage <= bytes.size(); page += kPage) {
    const std::uint32_t crc = plumb::io::crc32c(std::as_bytes(std::span(bytes).subspan(page, kData)));
    for (std::size_t i = 0; i < 4; ++i) bytes[page + kData + i] = static_cast<std::uint8_t>(crc >> (24 - 8 * i));
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::vector<std::uint8_t> bytes(data, data + size);
  if (std::string(PLUMB_FUZZ_READER) == "e57") repairE57Checksums(bytes);
  try {
    const auto reader = open(plumb::fuzz::memoryFile(bytes.data(), bytes.size()));
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
