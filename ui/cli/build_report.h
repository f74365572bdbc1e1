#pragma once
// What an octree build reports, as `plumb import` and `plumb simulate -o X.plumb` print it.

#include <cstddef>

namespace plumb::lod {
struct BuildReport;
}

namespace plumb::cli {

// The octree's nodes and size, the chunks, the peak resident memory against the budget and the
// time of each pass, one line each.
void printBuildReport(const lod::BuildReport& report, std::size_t memory_mb);

}  // namespace plumb::cli
