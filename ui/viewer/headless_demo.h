#pragma once
// What `plumb view` does where no display answers (a server, CI): the viewer's main job without
// a window. It grows the planes at a click on a corridor wall of the demo scan, as the Grow tool
// would from the demo's first view, and renders the result with its outlines into a PNG.

#include <string>

namespace plumb::viewer {

// Writes `png_path` (atomically) and prints what grew. Returns the exit status. Throws
// plumb::Error for what fails (no Vulkan device, the cache directory).
int runHeadlessDemo(const std::string& png_path, const std::string& gpu);

}  // namespace plumb::viewer
