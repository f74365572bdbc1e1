// A program that starts as plumb does (runWithHugePageHeap) and prints what its heap became: the
// GLIBC_TUNABLES it runs with and the VmFlags of the mapping that holds a 256 MiB block (`hg`:
// advised as huge pages). huge_pages_test.cpp runs it.

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

#include "engine/core/huge_pages.h"

namespace {

// The VmFlags line of the mapping in /proc/self/smaps that contains `address`.
std::string vmFlagsAt(std::uintptr_t address) {
  std::ifstream smaps("/proc/self/smaps");
  bool inside = false;
  for (std::string line; std::getline(smaps, line);) {
    std::uintptr_t begin = 0;
    std::uintptr_t end = 0;
    if (std::sscanf(line.c_str(), "%lx-%lx ", &begin, &end) == 2 && line.find(':') > line.find(' ')) {
      inside = begin <= address && address < end;  // a mapping's header line: "begin-end perms ..."
    } else if (inside && line.rfind("VmFlags:", 0) == 0) {
      return line;
    }
  }
  return "VmFlags: (no mapping found)";
}

}  // namespace

int main(int, char** argv) {
  plumb::runWithHugePageHeap(argv);
  std::vector<char> block(std::size_t{256} << 20, 1);
  const char* tunables = std::getenv("GLIBC_TUNABLES");
  std::printf("tunables %s\n%s\n", tunables == nullptr ? "(none)" : tunables,
              vmFlagsAt(reinterpret_cast<std::uintptr_t>(block.data() + block.size() / 2)).c_str());
  return 0;
}
