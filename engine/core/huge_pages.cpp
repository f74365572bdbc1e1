#include "engine/core/huge_pages.h"

#include <unistd.h>

#include <cstdlib>
#include <string>

namespace plumb {

namespace {

constexpr const char* kTunables =
    "glibc.malloc.hugetlb=1:glibc.malloc.mmap_threshold=1073741824:glibc.malloc.top_pad=67108864";

}  // namespace

void runWithHugePageHeap(char** argv) {
  if (kSanitizerOwnsTheHeap) return;
  const char* current = std::getenv("GLIBC_TUNABLES");
  const std::string tunables = current == nullptr ? "" : current;
  if (tunables.find("glibc.malloc.") != std::string::npos) return;
  const std::string wanted = tunables.empty() ? kTunables : tunables + ":" + kTunables;
  if (setenv("GLIBC_TUNABLES", wanted.c_str(), 1) != 0) return;
  execv("/proc/self/exe", argv);
  // Still here: the program goes on with glibc's defaults; GLIBC_TUNABLES stays set, so the
  // programs it starts have the heap on huge pages without running twice.
}

}  // namespace plumb
