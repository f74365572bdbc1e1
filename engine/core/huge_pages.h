#pragma once
// The heap on transparent huge pages, for the executables (plumb and the benchmarks).
//
// A full-detail grow or an import allocates a gigabyte in many vectors. On 4 KiB pages each first
// touch is a page fault (456,000 for one grow of the 10 M room), and on a virtual machine a fault
// costs several microseconds; the TLB misses over that memory cost as much again. Debian's kernel
// gives huge pages only to memory that asks for them (transparent_hugepage "madvise"), and glibc's
// malloc asks only when its tunable glibc.malloc.hugetlb is set, which it reads from the
// environment at start and nowhere else. So the program sets the tunables and runs itself again.
// docs/benchmarks.md ("Region growing", 2026-12-06) has the figures.

namespace plumb {

// A sanitizer build's allocator is its own and ignores glibc's tunables: nothing to set there.
inline constexpr bool kSanitizerOwnsTheHeap =
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
    true;
#else
    false;
#endif

// Call first in main, before any thread or allocation worth keeping. Unless the environment
// already names a malloc tunable of glibc (a user's own choice, or this function's, in the program
// it re-ran), sets GLIBC_TUNABLES to add
//   glibc.malloc.hugetlb=1               the heap and large blocks advised as huge pages
//   glibc.malloc.mmap_threshold=1 GiB    blocks up to 1 GiB from the heap, reused once freed,
//                                        instead of mapped fresh (and faulted in) each time
//   glibc.malloc.top_pad=64 MiB          the heap grown in steps of whole huge pages
// and executes /proc/self/exe with the same arguments. Returns where it does not
// (kSanitizerOwnsTheHeap; no /proc; the exec failing), and the program runs as it is.
// A user who wants none of it sets GLIBC_TUNABLES=glibc.malloc.hugetlb=0.
void runWithHugePageHeap(char** argv);

}  // namespace plumb
