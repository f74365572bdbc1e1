#pragma once
// Builds a Plumb octree from point clouds of any size with bounded memory (out of core), in
// parallel on oneTBB. docs/octree-format.md describes the result.
//
//   1. bounds:     read every input once for the bounding cube and the point count; skipped
//                  where every input's header states its bounds (LAS, LAZ): then the next pass
//                  measures them, and counts again if the points do not fit the headers' cube;
//   2. counting:   read again, counting points per cell of a 128^3 grid and along each axis
//                  (the framing box, framing.h);
//   3. chunking:   split the cube into chunks (octree cells) small enough to index in memory;
//   4. distribute: read a third time, appending each point to its chunk's temporary file;
//   5. index:      build each chunk's subtree in parallel (NodeIndexer), writing nodes as they
//                  finish; then the levels above the chunks from the chunk roots' points (held
//                  in memory: about 0.5 % of the points; for inputs of billions of points this
//                  part is not yet bounded by the budget);
//   6. finish:     write the node index and the header, fsync, rename into place.
// Temporary chunk files are unlinked as soon as they are created, so nothing is left behind
// however the build ends; the output appears only when complete (AtomicFile).

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "engine/io/point_reader.h"

namespace plumb::lod {

// One input: a name for messages and a way to open it (once per pass).
struct BuildSource {
  std::string name;
  std::function<std::unique_ptr<io::PointReader>()> open;
};

// The sources for point files, read with `options`.
std::vector<BuildSource> fileSources(const std::vector<std::string>& paths, const io::ReaderOptions& options = {});

struct BuildOptions {
  std::vector<BuildSource> sources;
  std::string output;
  // Memory budget for point data in the builder (the process needs some tens of MB more).
  std::size_t memory_mb = 2048;
  std::uint32_t leaf_max_points = 20'000;
  // Worker threads for indexing; 0: as many as cores, fewer when the budget calls for it.
  unsigned threads = 0;
  // Called with the phase name, points done and points in the phase (0 while unknown): one
  // call at a time, from the building thread or, while indexing, from a worker.
  std::function<void(std::string_view phase, std::uint64_t done, std::uint64_t total)> progress;
};

struct BuildReport {
  std::uint64_t points = 0;
  std::uint64_t skipped_non_finite = 0;
  std::uint64_t nodes = 0;
  std::uint32_t depth = 0;
  std::size_t chunks = 0;
  std::size_t largest_chunk_points = 0;
  unsigned index_threads = 0;
  std::uint64_t file_bytes = 0;
  std::vector<std::string> ignored_fields;  // "<input>: <field>"
  std::vector<std::string> scans;           // the scans each point keeps the index of; empty: one scan
  // Every input's header stated its bounds (LAS, LAZ), so no pass read them: the count measured
  // the points' own. `header_bounds_wrong`: the points did not fit the headers' bounds, or
  // these were loose, and the count was done again in the points' own cube.
  bool bounds_from_headers = false;
  bool header_bounds_wrong = false;
  double seconds_bounds = 0, seconds_counting = 0, seconds_distributing = 0, seconds_indexing = 0;
};

// Throws plumb::Error when an input cannot be read (naming the file and the place), when there
// are no points, or when the output cannot be written; nothing is left behind then.
BuildReport buildOctree(const BuildOptions& options);

}  // namespace plumb::lod
