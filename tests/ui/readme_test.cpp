// The README's account of the commands stays true: every command `plumb --help` lists has its
// section, and every option each command's help lists is named there, so a command or an option
// cannot land without the README saying what it does.

#include <gtest/gtest.h>

#include <regex>
#include <set>
#include <string>

#include "tests/support/plumb_command.h"
#include "tests/support/temp_directory.h"

namespace {

std::string readme() {
  return plumb::test::readFile(std::string(PLUMB_SOURCE_DIR) + "/README.md");
}

// The commands `plumb --help` lists: the indented words of its "Subcommands:" block.
std::set<std::string> commandsOfHelp(const std::string& help) {
  std::set<std::string> commands;
  const std::size_t block = help.find("Subcommands:");
  if (block == std::string::npos) return commands;
  const std::regex line(R"(\n  ([a-z]+) )");
  for (auto it = std::sregex_iterator(help.begin() + static_cast<std::ptrdiff_t>(block), help.end(), line);
       it != std::sregex_iterator(); ++it) {
    commands.insert((*it)[1]);
  }
  return commands;
}

std::set<std::string> longOptionsOf(const std::string& help) {
  std::set<std::string> options;
  const std::regex option(R"(--[a-z][a-z0-9-]*)");
  for (auto it = std::sregex_iterator(help.begin(), help.end(), option); it != std::sregex_iterator(); ++it) {
    options.insert(it->str());
  }
  options.erase("--help");
  return options;
}

TEST(Readme, EveryCommandAndOptionIsDescribed) {
  plumb::test::TempDirectory temp;
  const plumb::test::CommandOutcome help = plumb::test::runPlumb(temp, "--help");
  ASSERT_EQ(help.exit_code, 0) << help.err;
  const std::set<std::string> commands = commandsOfHelp(help.out);
  ASSERT_GE(commands.size(), 8u) << "the help's command list did not parse:\n" << help.out;
  const std::string text = readme();
  for (const std::string& command : commands) {
    EXPECT_NE(text.find("### plumb " + command + "\n"), std::string::npos) << "README has no section on " << command;
    const plumb::test::CommandOutcome command_help = plumb::test::runPlumb(temp, command + " --help");
    ASSERT_EQ(command_help.exit_code, 0) << command << ": " << command_help.err;
    for (const std::string& option : longOptionsOf(command_help.out)) {
      const std::regex named(option + "(?![a-z0-9-])");
      EXPECT_TRUE(std::regex_search(text, named)) << "README does not name `plumb " << command << " " << option << "`";
    }
  }
}

}  // namespace
