// plumb: the one executable. Each job is a subcommand (ui/cli/*_command.cpp); headless commands
// never touch a window system.

#include <CLI/App.hpp>
#include <CLI/Config.hpp>
#include <CLI/Formatter.hpp>
#include <cstdio>
#include <new>
#include <string>
#include <vector>

#include "engine/core/error.h"
#include "engine/core/huge_pages.h"
#include "ui/cli/command.h"

int main(int argc, char** argv) {
  plumb::runWithHugePageHeap(argv);
  CLI::App plumb("Plumb: precise planes, edges and corners from laser scans of buildings", "plumb");
  plumb.set_version_flag("--version", PLUMB_VERSION);
  plumb.require_subcommand(1);
  plumb.footer("Run 'plumb <command> --help' for the options of a command.");

  const std::vector<plumb::cli::Command> commands{
      plumb::cli::addExportCommand(plumb), plumb::cli::addGrowCommand(plumb),   plumb::cli::addImportCommand(plumb),
      plumb::cli::addInfoCommand(plumb),   plumb::cli::addRenderCommand(plumb), plumb::cli::addSectionCommand(plumb),
      plumb::cli::addSimulateCommand(plumb), plumb::cli::addViewCommand(plumb)};

  // CLI11 reports a mistyped command only as "A subcommand is required"; name it instead.
  std::string known;
  bool is_known = false;
  for (const plumb::cli::Command& command : commands) {
    known += " " + command.parser->get_name();
    is_known |= argc > 1 && command.parser->get_name() == argv[1];
  }
  if (argc > 1 && argv[1][0] != '-' && !is_known) {
    std::fprintf(stderr, "plumb: unknown command '%s'; the commands are:%s (see plumb --help)\n", argv[1],
                 known.c_str());
    return 2;
  }

  try {
    plumb.parse(argc, argv);
  } catch (const CLI::ParseError& error) {
    return plumb.exit(error);
  }

  for (const plumb::cli::Command& command : commands) {
    if (!command.parser->parsed()) continue;
    try {
      return command.run();
    } catch (const plumb::Error& error) {
      std::fprintf(stderr, "plumb %s: error: %s\n", command.parser->get_name().c_str(), error.what());
    } catch (const std::bad_alloc&) {
      std::fprintf(stderr, "plumb %s: error: out of memory; ask for less or free some memory\n",
                   command.parser->get_name().c_str());
    }
    return 1;
  }
  return 1;
}
