#pragma once
// Keeps Mesa's lavapipe mapped until the process ends. Lavapipe allocates a small block in a
// one-time initialisation and keeps it in a global; when the Vulkan loader unloads the driver
// at vkDestroyInstance, LeakSanitizer finds the block unreferenced in an unknown module and
// fails the test, although nothing leaks per instance. With the library kept (RTLD_NODELETE)
// the global still points at the block. A machine without lavapipe loses nothing.

#include <dlfcn.h>

namespace plumb::test {

inline void keepVulkanDriverLoaded() {
  static void* const kept = dlopen("libvulkan_lvp.so", RTLD_NOW | RTLD_NODELETE);
  (void)kept;
}

}  // namespace plumb::test
