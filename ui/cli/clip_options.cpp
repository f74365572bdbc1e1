#include "ui/cli/clip_options.h"

#include <CLI/App.hpp>
#include <cmath>

#include "engine/core/error.h"
#include "ui/cli/arguments.h"

namespace plumb::cli {

void addClipOptions(CLI::App& command, ClipArguments& arguments) {
  command.add_option("--clip-box", arguments.box,
                     "Keep the points inside a box: its centre, its size along its own axes (metres) and, "
                     "optionally, its turn about the vertical in degrees: CX,CY,CZ,SX,SY,SZ[,YAW]");
  command.add_flag("--clip-outside", arguments.outside, "Keep the points outside the --clip-box instead");
  command.add_option("--clip-plane", arguments.planes,
                     "Keep the points on the side of a plane its normal points to: PX,PY,PZ,NX,NY,NZ (a point of "
                     "it, its normal); repeat for more planes");
  command.add_option("--slice", arguments.slice,
                     "Keep a horizontal slice: the points from height Z up to Z + THICKNESS (metres): Z,THICKNESS");
}

view::ClipSettings clipSettingsOf(const ClipArguments& arguments) {
  view::ClipSettings region;
  if (!arguments.slice.empty()) {
    const std::vector<double> v = parseNumbers(arguments.slice, 2, 2, "--slice", "1.0,0.1");
    if (!(v[1] > 0.0)) throw Error("--slice: the thickness must be above 0; got " + arguments.slice);
    region.slice = true;
    region.slice_bottom_z = v[0];
    region.slice_thickness = v[1];
  }
  if (!arguments.box.empty()) {
    const std::vector<double> v = parseNumbers(arguments.box, 6, 7, "--clip-box", "2,3,1.5,4,5,3,30");
    const Eigen::Vector3d size(v[3], v[4], v[5]);
    if (!(size.minCoeff() > 0.0)) throw Error("--clip-box: each size must be above 0; got " + arguments.box);
    region.box = view::ClipBox{{v[0], v[1], v[2]}, 0.5 * size, v.size() == 7 ? v[6] * M_PI / 180.0 : 0.0};
  } else if (arguments.outside) {
    throw Error("--clip-outside needs a --clip-box");
  }
  region.keep_outside_box = arguments.outside;
  for (const std::string& text : arguments.planes) {
    const std::vector<double> v = parseNumbers(text, 6, 6, "--clip-plane", "0,0,1.2,0,0,-1");
    const Eigen::Vector3d normal(v[3], v[4], v[5]);
    if (!(normal.norm() > 0.0)) throw Error("--clip-plane: the normal must not be 0; got " + text);
    region.planes.push_back({{v[0], v[1], v[2]}, normal.normalized()});
  }
  view::checkClipRegion(region.region(), "clipping");
  return region;
}

}  // namespace plumb::cli
