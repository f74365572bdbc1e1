#pragma once
// The fuzz targets' inputs as a file: Plumb's readers take paths, the fuzzers hand over bytes.

#include <cstddef>
#include <cstdint>
#include <string>

namespace plumb::fuzz {

// Writes `size` bytes at `data` into one in-memory file (memfd) of the process, replacing what
// the previous call wrote, and returns a path that opens it ("/proc/self/fd/N"). Nothing touches
// the disk, so a million inputs cost no I/O. Traps when the memfd cannot be made or written: the
// harness is broken, not the input. Not thread-safe; libFuzzer and the replay run one input at a
// time.
std::string memoryFile(const std::uint8_t* data, std::size_t size);

}  // namespace plumb::fuzz
