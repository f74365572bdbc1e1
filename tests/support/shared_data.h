#pragma once
// The real scans in ../shared/data/real (beside the repository, never inside it). Tests that
// need one skip when it is absent: a user's fresh checkout has no ../shared. CI always has it,
// so there (CI=true) a missing file fails the test instead of skipping it quietly.

#include <cstdlib>
#include <filesystem>
#include <string>

namespace plumb::test {

inline std::filesystem::path sharedDataDirectory() {
  return std::filesystem::path(PLUMB_SOURCE_DIR).parent_path() / "shared" / "data" / "real";
}

// The path of real scan `name`, or an empty string when it is not there.
inline std::string sharedDataFile(const std::string& name) {
  const std::filesystem::path path = sharedDataDirectory() / name;
  return std::filesystem::exists(path) ? path.string() : std::string();
}

// The reference files of the scanner formats in ../shared/data/formats (their README says
// where each comes from), e.g. "e57/bunnyDouble.e57"; an empty string when absent.
inline std::string sharedFormatFile(const std::string& name) {
  const std::filesystem::path path = sharedDataDirectory().parent_path() / "formats" / name;
  return std::filesystem::exists(path) ? path.string() : std::string();
}

// True where ../shared/data must be present: in CI (the environment's CI=true).
inline bool sharedDataRequired() {
  const char* ci = std::getenv("CI");
  return ci != nullptr && std::string(ci) == "true";
}

}  // namespace plumb::test

// Ends the current test for a missing file of ../shared/data: a failure in CI, a skip elsewhere.
// `message` is streamed (it may hold <<).
#define PLUMB_SHARED_DATA_MISSING(message)                                                        \
  do {                                                                                            \
    if (::plumb::test::sharedDataRequired()) {                                                    \
      GTEST_FAIL() << message << " (CI=true: ../shared/data must be beside the repository)";      \
    }                                                                                             \
    GTEST_SKIP() << message << " (../shared/data is beside the repository in CI)";                \
  } while (false)

// Ends the current test (PLUMB_SHARED_DATA_MISSING) unless `variable` names an existing reference
// file of ../shared/data/formats.
#define PLUMB_REQUIRE_FORMAT_FILE(variable, name)                     \
  const std::string variable = ::plumb::test::sharedFormatFile(name); \
  if (variable.empty())                                               \
  PLUMB_SHARED_DATA_MISSING(name << " not found in " << ::plumb::test::sharedDataDirectory().parent_path() << "/formats")

// Ends the current test (PLUMB_SHARED_DATA_MISSING) unless `variable` (a std::string) names an
// existing real scan.
#define PLUMB_REQUIRE_SHARED_DATA(variable, name)                   \
  const std::string variable = ::plumb::test::sharedDataFile(name); \
  if (variable.empty()) PLUMB_SHARED_DATA_MISSING(name << " not found in " << ::plumb::test::sharedDataDirectory())
