// A COPC file opened in place and grown on (docs/benchmarks.md). Prints, asserts nothing.
//
//   plumb_bench_copc [FILE] [--seed X,Y,Z] [--view-distance M] [--mosaic K DIR]
//
// FILE defaults to ../shared/data/formats/copc/lone-star.copc.laz. --mosaic writes 2^K x 2^K
// copies of FILE side by side into DIR (tests/support/copc_mosaic.h) and measures that instead:
// the reference files hold at most 15 nodes, too few to show what a click leaves unread. Prints the time to open the
// file as an octree (the LAS header, the info VLR and every hierarchy page; best of 5), the
// nodes and points it holds, then one click as `plumb grow` makes it (the data's spacing at the
// click, then the grow, from an empty node cache): the nodes and the bytes it loaded against the
// file's, and the times. Without --seed, the click is the first point of the deepest node nearest
// the middle of the bounds.

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <limits>
#include <memory>
#include <optional>
#include <string>

#include "engine/core/huge_pages.h"
#include "engine/lod/node_cache.h"
#include "engine/lod/octree.h"
#include "reco/data_at_click.h"
#include "reco/parameters.h"
#include "reco/region_grower.h"
#include "tests/support/copc_mosaic.h"

namespace {

using namespace plumb;
using Clock = std::chrono::steady_clock;

double millisecondsSince(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

// The first point of the deepest node whose cell centre lies nearest the middle of the bounds.
Eigen::Vector3d defaultSeed(const lod::Octree& octree) {
  const lod::Box3& bounds = octree.header().bounds;
  Eigen::Vector3d middle;
  for (int a = 0; a < 3; ++a)
    middle[a] = 0.5 * (bounds.min[static_cast<std::size_t>(a)] + bounds.max[static_cast<std::size_t>(a)]);
  const lod::NodeInfo* best = nullptr;
  double best_distance = std::numeric_limits<double>::infinity();
  for (const lod::NodeInfo& node : octree.nodes()) {
    if (node.key.level != octree.header().depth || node.point_count == 0) continue;
    const lod::Box3 box = octree.cube().cellBox(node.key);
    Eigen::Vector3d centre;
    for (std::size_t a = 0; a < 3; ++a) centre[static_cast<int>(a)] = 0.5 * (box.min[a] + box.max[a]);
    if (const double d = (centre - middle).squaredNorm(); d < best_distance) {
      best_distance = d;
      best = &node;
    }
  }
  const lod::NodePoints points = octree.load(*best);
  const auto p = points.position(0);
  return {p[0], p[1], p[2]};
}

}  // namespace

int main(int argc, char** argv) {
  plumb::runWithHugePageHeap(argv);  // as plumb runs
  std::string path =
      (std::filesystem::path(PLUMB_SOURCE_DIR).parent_path() / "shared/data/formats/copc/lone-star.copc.laz").string();
  std::optional<Eigen::Vector3d> seed;
  double view_distance = 30.0;
  int mosaic_levels = 0;
  std::string mosaic_directory;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--seed") == 0 && i + 1 < argc) {
      Eigen::Vector3d s;
      if (std::sscanf(argv[++i], "%lf,%lf,%lf", &s.x(), &s.y(), &s.z()) != 3) {
        std::fprintf(stderr, "--seed wants X,Y,Z\n");
        return 2;
      }
      seed = s;
    } else if (std::strcmp(argv[i], "--view-distance") == 0 && i + 1 < argc) {
      view_distance = std::atof(argv[++i]);
    } else if (std::strcmp(argv[i], "--mosaic") == 0 && i + 2 < argc) {
      mosaic_levels = std::atoi(argv[++i]);
      mosaic_directory = argv[++i];
    } else {
      path = argv[i];
    }
  }

  if (!std::filesystem::exists(path)) {
    std::printf("skipped: %s not found (../shared/data is beside the repository)\n", path.c_str());
    return 0;
  }
  if (mosaic_levels > 0) {
    const std::string tile = path;
    path = (std::filesystem::path(mosaic_directory) /
            ("mosaic-" + std::to_string(1 << mosaic_levels) + "x" + std::to_string(1 << mosaic_levels) + ".copc.laz"))
               .string();
    const auto start = Clock::now();
    test::writeCopcMosaic(tile, mosaic_levels, path);
    std::printf("wrote %s from %s in %.0f ms\n", path.c_str(), tile.c_str(), millisecondsSince(start));
  }

  double open_ms = std::numeric_limits<double>::infinity();
  std::shared_ptr<const lod::Octree> octree;
  for (int run = 0; run < 5; ++run) {
    const auto start = Clock::now();
    octree = lod::Octree::open(path);
    open_ms = std::min(open_ms, millisecondsSince(start));
  }
  std::uint64_t stored_bytes = 0;
  for (const lod::NodeInfo& node : octree->nodes()) stored_bytes += node.bytes;
  std::printf("%s\n  %s, %llu bytes\n", path.c_str(), octree->format().c_str(),
              static_cast<unsigned long long>(std::filesystem::file_size(path)));
  std::printf("  open (header, info, hierarchy): %.3f ms (best of 5)\n", open_ms);
  std::printf("  nodes %zu in %u levels, %llu points, %llu bytes of node chunks\n", octree->nodes().size(),
              octree->header().depth + 1, static_cast<unsigned long long>(octree->header().point_count),
              static_cast<unsigned long long>(stored_bytes));

  if (!seed) seed = defaultSeed(*octree);
  lod::NodeCache cache(octree, std::size_t{1} << 30);
  const auto measuring = Clock::now();
  const reco::DataAtClick data = reco::dataAtClick(cache, *seed);
  const double measure_ms = millisecondsSince(measuring);
  const reco::GrowParameters parameters =
      reco::parametersForView(reco::viewFromDistance(*seed, view_distance), {}, data);
  const reco::GrowSnapshot result = reco::growRegions(cache, parameters);
  const lod::NodeCacheStats stats = cache.stats();

  std::uint64_t grown = 0;
  for (const auto& segment : result.segments) grown += segment.points;
  std::printf("  click %.3f %.3f %.3f seen from %.0f m: spacing at the click %.3f m (measured in %.2f ms)\n", seed->x(),
              seed->y(), seed->z(), view_distance, data.spacing_m, measure_ms);
  std::printf("  grow: %.2f ms, %s, %zu segments, %llu points, level %u, %llu cells\n", result.elapsed_ms,
              result.converged ? "converged" : "stopped", result.segments.size(),
              static_cast<unsigned long long>(grown), result.level,
              static_cast<unsigned long long>(result.cells_visited));
  std::printf(
      "  nodes loaded (click and grow): %llu of %zu (%.1f %%), %llu of %llu chunk bytes (%.1f %%)\n",
      static_cast<unsigned long long>(stats.misses), octree->nodes().size(),
      100.0 * static_cast<double>(stats.misses) / static_cast<double>(octree->nodes().size()),
      static_cast<unsigned long long>(stats.bytes_read), static_cast<unsigned long long>(stored_bytes),
      100.0 * static_cast<double>(stats.bytes_read) / static_cast<double>(std::max<std::uint64_t>(stored_bytes, 1)));
  return 0;
}
