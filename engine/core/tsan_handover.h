#pragma once
// Hand-overs through oneTBB that ThreadSanitizer must be told about. Debian's libtbb is not built
// for ThreadSanitizer, so it cannot see that what a thread wrote before handing a task to oneTBB
// happens before a worker runs the task: release before the hand-over, acquire when the task
// starts, on the same address. Nothing outside a ThreadSanitizer build.

#if defined(__SANITIZE_THREAD__)
#include <sanitizer/tsan_interface.h>
#define PLUMB_TSAN_RELEASE(address) __tsan_release(address)
#define PLUMB_TSAN_ACQUIRE(address) __tsan_acquire(address)
#else
#define PLUMB_TSAN_RELEASE(address) static_cast<void>(address)
#define PLUMB_TSAN_ACQUIRE(address) static_cast<void>(address)
#endif
