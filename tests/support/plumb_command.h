#pragma once
// The plumb binary run as a user runs it, for the tests of its commands.

#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <string>

#include "tests/support/temp_directory.h"

namespace plumb::test {

struct CommandOutcome {
  int exit_code;  // -1 when the process did not exit normally
  std::string out;
  std::string err;
};

// Runs `plumb ARGUMENTS` (shell words) with no standard input; its output goes through two files
// in `dir`, removed again.
inline CommandOutcome runPlumb(const TempDirectory& dir, const std::string& arguments) {
  const std::string out = dir.file("stdout.txt"), err = dir.file("stderr.txt");
  const std::string command = std::string(PLUMB_BINARY) + " " + arguments + " </dev/null >" + out + " 2>" + err;
  const int status = std::system(command.c_str());
  CommandOutcome run{WIFEXITED(status) ? WEXITSTATUS(status) : -1, readFile(out), readFile(err)};
  std::filesystem::remove(out);
  std::filesystem::remove(err);
  return run;
}

}  // namespace plumb::test
