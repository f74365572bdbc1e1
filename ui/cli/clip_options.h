#pragma once
// The clipping options of the commands that draw a cloud (plumb render, plumb view): a box, its
// inside or outside kept, clip planes and a horizontal slice, as view::ClipSettings.

#include <string>
#include <vector>

#include "engine/view/clip_region.h"

namespace CLI {
class App;
}

namespace plumb::cli {

struct ClipArguments {
  std::string box;  // "CX,CY,CZ,SX,SY,SZ[,YAW_DEG]"
  bool outside = false;
  std::vector<std::string> planes;  // "PX,PY,PZ,NX,NY,NZ" each
  std::string slice;                // "Z,THICKNESS"
};

void addClipOptions(CLI::App& command, ClipArguments& arguments);

// Throws plumb::Error naming the option for a malformed or impossible value.
view::ClipSettings clipSettingsOf(const ClipArguments& arguments);

}  // namespace plumb::cli
