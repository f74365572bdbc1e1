// plumb import: point files to a Plumb octree.

#include <CLI/App.hpp>
#include <CLI/Config.hpp>
#include <CLI/Formatter.hpp>
#include <cstdio>
#include <memory>

#include "engine/lod/octree_builder.h"
#include "ui/cli/arguments.h"
#include "ui/cli/build_report.h"
#include "ui/cli/command.h"
#include "ui/cli/progress_line.h"

namespace plumb::cli {
namespace {

struct ImportOptions {
  std::vector<std::string> inputs;
  std::string output;
  std::size_t memory_mb = 2048;
  std::string columns;
};

}  // namespace

Command addImportCommand(CLI::App& plumb) {
  auto options = std::make_shared<ImportOptions>();
  CLI::App* sub = plumb.add_subcommand(
      "import", "Build an octree from point files (PLY, LAS, LAZ, COPC, PCD, E57, XYZ/TXT/PTS/CSV)");
  sub->footer(
      "Example: plumb import scan1.las scan2.ply -o site.plumb --memory-mb 4096\n"
      "Kept: positions, colour, intensity; where the inputs hold several scans (each E57 data3D, each other "
      "file), the scan of every point. Fields not kept are listed after the import. The README lists what each "
      "format's reader reads.");
  sub->add_option("inputs", options->inputs, "Point files, merged into one cloud")
      ->required()
      ->check(CLI::ExistingFile);
  sub->add_option("-o,--output", options->output, "The octree to write (.plumb)")->required();
  sub->add_option("--memory-mb", options->memory_mb, "Memory budget for the build in MiB, whatever the input size")
      ->check(CLI::Range(64, 1 << 20))
      ->capture_default_str();
  sub->add_option("--columns", options->columns,
                  "ASCII inputs: the meaning of each column, e.g. x,y,z,i,r,g,b (_ skips a column)");

  auto run = [options]() -> int {
    lod::BuildOptions build;
    io::ReaderOptions reader;
    reader.columns = options->columns;
    build.sources = lod::fileSources(options->inputs, reader);
    build.output = options->output;
    build.memory_mb = options->memory_mb;
    ProgressLine progress("import");
    build.progress = [&](std::string_view phase, std::uint64_t done, std::uint64_t total) {
      progress.update(phase, done, total);
    };
    const lod::BuildReport report = lod::buildOctree(build);
    progress.finish();

    std::printf("imported %s points from %zu file%s into %s\n", withThousands(report.points).c_str(),
                options->inputs.size(), options->inputs.size() == 1 ? "" : "s", options->output.c_str());
    if (report.skipped_non_finite > 0) {
      std::printf("  skipped  %s points without a valid position (NaN or infinite coordinates, or marked invalid)\n",
                  withThousands(report.skipped_non_finite).c_str());
    }
    for (const std::string& field : report.ignored_fields) std::printf("  ignored  %s\n", field.c_str());
    if (!report.scans.empty()) {
      std::printf("  scans    %zu, each point keeps its scan (plumb render --colour scan; plumb info lists them)\n",
                  report.scans.size());
    }
    printBuildReport(report, options->memory_mb);
    return 0;
  };
  return {sub, run};
}

}  // namespace plumb::cli
