#pragma once
// What `plumb grow` writes: the result as JSON (docs/grow-json.md) and as a glTF 2.0 binary
// (segment polygons as triangle meshes, edges as lines, corners as points). Both atomic.

#include <Eigen/Core>
#include <string>

#include "reco/parameters.h"
#include "reco/region_grower.h"

namespace plumb::cli {

struct GrowReport {
  std::string cloud;
  Eigen::Vector3d seed;
  reco::GrowParameters parameters;
  const reco::GrowSnapshot& result;
  double first_progress_ms = -1.0;
};

// Throws plumb::Error when the file cannot be written; leaves no partial file.
void writeGrowJson(const GrowReport& report, const std::string& path);
void writeGrowGltf(const reco::GrowSnapshot& result, const std::string& path);

}  // namespace plumb::cli
