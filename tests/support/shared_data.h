#pragma once
// The real scans in ../shared/data/real (beside the repository, never inside it). Tests that
// need one skip when it is absent: a user's fresh checkout has no ../shared; CI always has it.

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

}  // namespace plumb::test

// Skips the current test unless `variable` names an existing reference file of ../shared/data/formats.
#define PLUMB_REQUIRE_FORMAT_FILE(variable, name)                                             \
  const std::string variable = ::plumb::test::sharedFormatFile(name);                         \
  if (variable.empty())                                                                       \
  GTEST_SKIP() << name << " not found in " << ::plumb::test::sharedDataDirectory().parent_path() \
               << "/formats (../shared/data is beside the repository in CI)"

// Skips the current test unless `variable` (a std::string) names an existing real scan.
#define PLUMB_REQUIRE_SHARED_DATA(variable, name)                                  \
  const std::string variable = ::plumb::test::sharedDataFile(name);                \
  if (variable.empty())                                                            \
  GTEST_SKIP() << name << " not found in " << ::plumb::test::sharedDataDirectory() \
               << " (../shared/data is beside the repository in CI)"
