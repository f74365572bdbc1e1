#pragma once
// The built-in demo of `plumb view` (and scripts/run): a simulated scan of the office scene
// (reco/sim, a corridor and three offices), generated once into the user's cache directory and
// reused, with the simulator's ground truth beside it.

#include <filesystem>
#include <functional>
#include <string>
#include <string_view>

#include "engine/view/camera.h"

namespace plumb::viewer {

struct DemoScan {
  std::filesystem::path octree;  // plumb's octree of the scan
  std::filesystem::path truth;   // the simulator's truth (docs/simulator.md), world coordinates
  view::Camera home;             // in the corridor, looking along it
};

// $XDG_CACHE_HOME/plumb, else $HOME/.cache/plumb; created if missing. Throws plumb::Error when
// neither variable is set or the folder cannot be made.
std::filesystem::path userCacheDirectory();

// The demo scan, simulated and indexed first if the cache does not hold it yet (a few seconds;
// `progress` hears the phases). Throws plumb::Error naming what failed; a half-made demo is
// never left behind (outputs appear atomically).
DemoScan ensureDemoScan(const std::function<void(std::string_view phase, double fraction)>& progress = {});

}  // namespace plumb::viewer
