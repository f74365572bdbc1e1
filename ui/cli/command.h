#pragma once
// A subcommand of `plumb`: its CLI11 parser and what to run once the arguments are parsed.

#include <functional>

namespace CLI {
class App;
}

namespace plumb::cli {

struct Command {
  CLI::App* parser;
  // Runs the command; returns the process exit code. Throws plumb::Error for failures that
  // main() reports on stderr.
  std::function<int()> run;
};

// Each adds its subcommand to `plumb` (one file per command).
Command addSimulateCommand(CLI::App& plumb);
Command addExportCommand(CLI::App& plumb);
Command addGrowCommand(CLI::App& plumb);
Command addImportCommand(CLI::App& plumb);
Command addInfoCommand(CLI::App& plumb);
Command addRenderCommand(CLI::App& plumb);
Command addSectionCommand(CLI::App& plumb);
Command addViewCommand(CLI::App& plumb);

}  // namespace plumb::cli
