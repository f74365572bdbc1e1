#include "ui/cli/build_report.h"

#include <sys/resource.h>

#include <algorithm>
#include <cstdio>
#include <string>

#include "engine/lod/octree_builder.h"
#include "ui/cli/arguments.h"

namespace plumb::cli {

void printBuildReport(const lod::BuildReport& report, std::size_t memory_mb) {
  std::printf("  octree   %s nodes, %u levels, %.1f MB\n", withThousands(report.nodes).c_str(), report.depth + 1,
              static_cast<double>(report.file_bytes) / 1e6);
  std::printf("  chunks   %zu (largest %s points), indexed on %u thread%s within %zu MiB\n", report.chunks,
              withThousands(report.largest_chunk_points).c_str(), report.index_threads,
              report.index_threads == 1 ? "" : "s", memory_mb);
  rusage usage{};
  ::getrusage(RUSAGE_SELF, &usage);
  std::printf("  memory   peak resident %.0f MB (budget %zu MiB)\n", static_cast<double>(usage.ru_maxrss) / 1024.0,
              memory_mb);
  // Inputs whose headers state their bounds (LAS, LAZ) are read twice, not three times.
  char bounds_pass[32];
  std::snprintf(bounds_pass, sizeof bounds_pass, "bounds %.2f", report.seconds_bounds);
  const std::string bounds = !report.bounds_from_headers ? bounds_pass
                             : report.header_bounds_wrong
                                 ? "bounds from the headers, which the points did not fit: counted twice"
                                 : "bounds from the headers";
  const double seconds =
      report.seconds_bounds + report.seconds_counting + report.seconds_distributing + report.seconds_indexing;
  std::printf(
      "  time     %.2f s (%s, counting %.2f, distributing %.2f, indexing %.2f): %.2f million points per second\n",
      seconds, bounds.c_str(), report.seconds_counting, report.seconds_distributing, report.seconds_indexing,
      static_cast<double>(report.points) / std::max(seconds, 1e-9) / 1e6);
}

}  // namespace plumb::cli
