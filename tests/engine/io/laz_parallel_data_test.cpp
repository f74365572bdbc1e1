// LAZ decoded by chunks in parallel (laz_chunk_window.h) against the sequential decoder on every
// reference LAZ and COPC file of ../shared/data/formats: the same records, bit for bit, whatever
// the chunks in flight, the threads of the arena and the batch sizes. COPC files are LAZ 1.4 with
// variable chunks (one per octree node) and so the reference files with the most chunks. Errors
// in order are tested on edited files in laz_data_test.cpp and laz_reader_test.cpp.

#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <cstddef>
#include <string>
#include <vector>

#include "engine/io/las_reader.h"
#include "tests/support/shared_data.h"

namespace plumb::io {
namespace {

std::vector<std::byte> recordsOf(const std::string& path, std::size_t chunks_in_flight, std::size_t batch) {
  auto reader = openLasRecords(path, LasReadOptions{.laz_chunks_in_flight = chunks_in_flight});
  std::vector<std::byte> all, some;
  while (reader->readRecords(some, batch) > 0) all.insert(all.end(), some.begin(), some.end());
  return all;
}

const char* const kFiles[] = {
    "laz/point10.las.laz",
    "laz/point-time.las.laz",
    "laz/point-color.las.laz",
    "laz/point-color-time.las.laz",
    "laz/extrabytes.laz",
    "laz/point10-1.0.laz",
    "laz/no-points-1.3.laz",
    "laz/simple.laz",
    "laz/simple-laszip-compressor-version-1.2r0.laz",
    "laz/laszip-generated_with2bytespadding.laz",
    "laz/liblas-generated.laz",
    "laz/autzen_trim.laz",
    "laz/point-time-1.4.las.laz",
    "laz/1_4_w_evlr.laz",
    "laz/autzen-bmx-2010.laz",
    "laz/append-bug.laz",
    "laz/las_with_several_extra_byte_bloc.laz",
    "copc/1.2-with-color.copc.laz",
    "copc/autzen.copc.laz",
    "copc/autzen_clip_4326.copc.laz",
    "copc/autzen_clip_native.copc.laz",
    "copc/lone-star.copc.laz",
    "copc/simple_with_page.copc.laz",
};

TEST(LazParallelData, ChunksInParallelGiveTheSequentialRecordsOnEveryReferenceFile) {
  for (const char* file : kFiles) {
    SCOPED_TRACE(file);
    const std::string path = test::sharedFormatFile(file);
    if (path.empty()) continue;  // absent reference files are skipped one by one
    const std::vector<std::byte> sequential = recordsOf(path, 1, 65'536);
    for (const int threads : {1, 3}) {
      tbb::task_arena arena(threads);
      arena.execute([&] {
        for (const std::size_t in_flight : {std::size_t{2}, std::size_t{5}}) {
          SCOPED_TRACE(std::to_string(threads) + " threads, " + std::to_string(in_flight) + " chunks in flight");
          EXPECT_TRUE(recordsOf(path, in_flight, 7'777) == sequential);
        }
      });
    }
    EXPECT_TRUE(recordsOf(path, 0, 1'000'000) == sequential);  // a batch of more than one chunk
  }
}

}  // namespace
}  // namespace plumb::io
