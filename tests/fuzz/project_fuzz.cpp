// libFuzzer target for the project file (cad/project_file.h, docs/project-file.md):
// readProjectFile, which parses, validates every field and checks the project's rules
// (cad/project_validation.h). Any input must end in a project or a plumb::Error, never in a crash,
// a hang or a sanitizer report. Run by scripts/fuzz, and replayed in the test suite
// (fuzz_replay_main.cpp).

#include <cstddef>
#include <cstdint>

#include "cad/project_file.h"
#include "cad/project_validation.h"
#include "engine/core/error.h"
#include "tests/fuzz/memory_file.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    const plumb::cad::Project project = plumb::cad::readProjectFile(plumb::fuzz::memoryFile(data, size));
    // What the reader returns is a valid project: the exports and the viewer rely on it.
    if (plumb::cad::findProjectProblem(project)) __builtin_trap();
  } catch (const plumb::Error&) {
    // Malformed input, reported: what the reader must do.
  }
  return 0;
}
