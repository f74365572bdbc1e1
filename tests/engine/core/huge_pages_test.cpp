#include "engine/core/huge_pages.h"

#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdio>
#include <cstdlib>
#include <string>

namespace plumb {
namespace {

// The probe's output, run with `environment` (words for env(1)) and nothing else changed.
std::string runProbe(const std::string& environment) {
  const std::string command = "env " + environment + " " PLUMB_HUGE_PAGES_PROBE;
  FILE* pipe = popen(command.c_str(), "r");
  if (pipe == nullptr) return "";
  std::string out;
  char buffer[512];
  while (std::fgets(buffer, sizeof buffer, pipe) != nullptr) out += buffer;
  const int status = pclose(pipe);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << command;
  return out;
}

// Release and Debug builds alike (the sanitizers bring their own allocator and are left alone).
TEST(HugePages, TheHeapIsAdvisedAsHugePagesInReleaseBuilds) {
  if (kSanitizerOwnsTheHeap) GTEST_SKIP() << "a sanitizer's allocator ignores glibc's tunables";
  const std::string out = runProbe("-u GLIBC_TUNABLES");
  EXPECT_NE(out.find("tunables glibc.malloc.hugetlb=1:"), std::string::npos) << out;
  EXPECT_NE(out.find(" hg"), std::string::npos) << out;
}

TEST(HugePages, AUsersOwnMallocTunablesAreKeptInReleaseBuilds) {
  if (kSanitizerOwnsTheHeap) GTEST_SKIP() << "a sanitizer's allocator ignores glibc's tunables";
  const std::string out = runProbe("GLIBC_TUNABLES=glibc.malloc.hugetlb=0");
  EXPECT_NE(out.find("tunables glibc.malloc.hugetlb=0\n"), std::string::npos) << out;
  EXPECT_EQ(out.find(" hg"), std::string::npos) << out;
}

TEST(HugePages, OtherTunablesAreKeptBesideThemInReleaseBuilds) {
  if (kSanitizerOwnsTheHeap) GTEST_SKIP() << "a sanitizer's allocator ignores glibc's tunables";
  const std::string out = runProbe("GLIBC_TUNABLES=glibc.rtld.optional_static_tls=2048");
  EXPECT_NE(out.find("tunables glibc.rtld.optional_static_tls=2048:glibc.malloc.hugetlb=1:"), std::string::npos) << out;
  EXPECT_NE(out.find(" hg"), std::string::npos) << out;
}

}  // namespace
}  // namespace plumb
