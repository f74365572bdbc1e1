// plumb info: what an octree (Plumb's, or a COPC file read in place) holds, and whether it is intact.

#include <CLI/App.hpp>
#include <CLI/Config.hpp>
#include <CLI/Formatter.hpp>
#include <cstdio>
#include <map>
#include <memory>

#include "engine/lod/framing.h"
#include "engine/lod/octree.h"
#include "ui/cli/arguments.h"
#include "ui/cli/command.h"

namespace plumb::cli {

Command addInfoCommand(CLI::App& plumb) {
  auto path = std::make_shared<std::string>();
  auto verify = std::make_shared<bool>(false);
  CLI::App* sub = plumb.add_subcommand("info", "Describe an octree: points, bounds, levels, nodes, spacing");
  sub->add_option("octree", *path, "An octree built by 'plumb import', or a COPC file (.copc.laz)")
      ->required()
      ->check(CLI::ExistingFile);
  sub->add_flag("--verify", *verify, "Read every node and check it (checksums; COPC: every chunk decodes)");

  auto run = [path, verify]() -> int {
    const auto octree = lod::Octree::open(*path);
    const lod::OctreeHeader& h = octree->header();
    std::printf("%s\n", path->c_str());
    std::printf("  format      %s\n", octree->format().c_str());
    std::printf("  points      %s", withThousands(h.point_count).c_str());
    if (h.skipped_non_finite > 0) {
      std::printf(" (%s input points skipped: no valid position)", withThousands(h.skipped_non_finite).c_str());
    }
    std::printf("\n  inputs      %u file%s\n", h.input_files, h.input_files == 1 ? "" : "s");
    std::printf("  bounds      x %.3f .. %.3f\n              y %.3f .. %.3f\n              z %.3f .. %.3f\n",
                h.bounds.min[0], h.bounds.max[0], h.bounds.min[1], h.bounds.max[1], h.bounds.min[2], h.bounds.max[2]);
    const lod::Box3 framing = lod::framingBox(*octree);
    std::printf(
        "  framing     x %.3f .. %.3f\n              y %.3f .. %.3f\n              z %.3f .. %.3f\n"
        "              (%.1f %% of the points along each axis%s)\n",
        framing.min[0], framing.max[0], framing.min[1], framing.max[1], framing.min[2], framing.max[2],
        100.0 * (1.0 - 2.0 * lod::kFramingQuantile), h.framing ? "" : ", from the shallowest levels");
    std::printf("  cube        origin %.3f %.3f %.3f, size %.3f m\n", h.cube.origin[0], h.cube.origin[1],
                h.cube.origin[2], h.cube.size);
    std::string attributes;
    if (h.attributes & lod::kHasColour) attributes += " colour";
    if (h.attributes & lod::kHasIntensity) attributes += " intensity";
    if (h.attributes & lod::kHasScanIndex) attributes += " scan";
    std::printf("  attributes  position%s\n", attributes.c_str());
    // A cloud merged from many scans lists the first ones: the rest are a count.
    constexpr std::size_t kScansListed = 20;
    for (std::size_t i = 0; i < h.scans.size() && i < kScansListed; ++i) {
      std::printf("  %s %5zu  %s\n", i == 0 ? "scans" : "     ", i, h.scans[i].c_str());
    }
    if (h.scans.size() > kScansListed) std::printf("              ... and %zu more\n", h.scans.size() - kScansListed);
    std::printf("  nodes       %s in %u levels (leaves hold up to %s points)\n", withThousands(h.node_count).c_str(),
                h.depth + 1, withThousands(h.leaf_max_points).c_str());

    std::map<std::uint32_t, std::pair<std::uint64_t, std::uint64_t>> per_level;  // nodes, points
    for (const lod::NodeInfo& node : octree->nodes()) {
      ++per_level[node.key.level].first;
      per_level[node.key.level].second += node.point_count;
    }
    std::printf("  level  spacing      nodes        points\n");
    for (const auto& [level, counts] : per_level) {
      std::printf("  %5u  %9.4f m  %9s  %12s\n", level, octree->spacing(level), withThousands(counts.first).c_str(),
                  withThousands(counts.second).c_str());
    }
    if (*verify) {
      for (const lod::NodeInfo& node : octree->nodes()) octree->load(node);  // throws on a bad node
      std::printf("  verified    every node's data\n");
    }
    return 0;
  };
  return {sub, run};
}

}  // namespace plumb::cli
