// LAZ decoding speed (docs/benchmarks.md, issue 20 point 2). Prints, asserts nothing.
//
//   plumb_bench_laz [FILE...] [--passes N]
//
// Without FILE: the reference LAZ files of ../shared/data/formats with at least 1000 points (the
// LAS/LAZ pairs of both coders, the layered file without a twin) and lone-star.copc.laz. For each
// file, the best of N passes (default 5) of reading every record through openLasRecords, in
// batches of 65 536: one thread (the reader decodes each chunk as it reads it) and all threads
// (chunks decoded ahead on oneTBB's workers, laz_chunk_window.h), in million points per second
// and per CPU-second (the process's CPU time: the speed per core that a loaded machine hides from
// the wall clock). The load average is printed first: the figures mean little on a
// machine that other work keeps busy.

#include <tbb/task_arena.h>
#include <time.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "engine/core/huge_pages.h"
#include "engine/io/las_reader.h"

namespace {

using Clock = std::chrono::steady_clock;

const char* const kDefaultFiles[] = {
    "laz/point-time.las.laz",                    // point-wise, format 1
    "laz/point-color-time.las.laz",              // point-wise, format 3
    "laz/simple.laz",                            // point-wise, format 3
    "laz/autzen_trim.laz",                       // point-wise, format 3, 3 chunks
    "laz/1_4_w_evlr.laz",                        // layered, format 6
    "laz/autzen-bmx-2010.laz",                   // layered, format 7
    "laz/append-bug.laz",                        // layered, format 8 + extra bytes
    "laz/las_with_several_extra_byte_bloc.laz",  // layered, format 8 + extra bytes
    "copc/lone-star.copc.laz",                   // layered, format 6, variable chunks
};

struct Pass {
  double seconds = 0;      // wall-clock
  double cpu_seconds = 0;  // of the process, all threads together
  std::uint64_t points = 0;
};

double processCpuSeconds() {
  timespec now{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &now);
  return static_cast<double>(now.tv_sec) + 1e-9 * static_cast<double>(now.tv_nsec);
}

Pass bestOf(const std::string& path, std::size_t chunks_in_flight, int passes) {
  Pass best{1e30, 0, 0};
  std::vector<std::byte> records;
  for (int p = 0; p < passes; ++p) {
    const auto start = Clock::now();
    const double cpu_start = processCpuSeconds();
    auto reader = plumb::io::openLasRecords(path, {.laz_chunks_in_flight = chunks_in_flight});
    std::uint64_t points = 0;
    while (const std::size_t n = reader->readRecords(records, 65'536)) points += n;
    const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
    if (seconds < best.seconds) best = {seconds, processCpuSeconds() - cpu_start, points};
  }
  return best;
}

std::string loadAverage() {
  std::ifstream in("/proc/loadavg");
  std::string line;
  std::getline(in, line);
  return line;
}

}  // namespace

int main(int argc, char** argv) {
  plumb::runWithHugePageHeap(argv);  // as plumb runs
  std::vector<std::string> files;
  int passes = 5;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--passes") == 0 && i + 1 < argc) {
      passes = std::max(1, std::atoi(argv[++i]));
    } else {
      files.emplace_back(argv[i]);
    }
  }
  if (files.empty()) {
    const std::filesystem::path formats =
        std::filesystem::path(PLUMB_SOURCE_DIR).parent_path() / "shared" / "data" / "formats";
    for (const char* file : kDefaultFiles) {
      if (std::filesystem::exists(formats / file)) files.push_back((formats / file).string());
    }
  }
  const int threads = tbb::this_task_arena::max_concurrency();
  std::printf("threads: %d; load average: %s\n", threads, loadAverage().c_str());
  std::printf("%-38s %8s | %-25s | %-25s\n", "", "", "1 thread, M points/s", "all threads, M points/s");
  std::printf("%-38s %8s | %12s %12s | %12s %12s\n", "file", "points", "wall", "per CPU-s", "wall", "per CPU-s");
  for (const std::string& path : files) {
    try {
      const Pass one = bestOf(path, 1, passes);
      const Pass all = bestOf(path, 0, passes);
      const auto rate = [](std::uint64_t points, double seconds) {
        return static_cast<double>(points) / seconds / 1e6;
      };
      std::printf("%-38s %8llu | %12.2f %12.2f | %12.2f %12.2f\n",
                  std::filesystem::path(path).filename().string().c_str(), static_cast<unsigned long long>(one.points),
                  rate(one.points, one.seconds), rate(one.points, one.cpu_seconds), rate(all.points, all.seconds),
                  rate(all.points, all.cpu_seconds));
    } catch (const std::exception& error) {
      std::printf("%s: %s\n", path.c_str(), error.what());
      return 1;
    }
  }
  std::printf("load average after: %s\n", loadAverage().c_str());
  return 0;
}
