#pragma once
// The intensities that the "intensity" colour spreads from black to white. LAS asks for
// intensities scaled to 16 bits, but many files keep their scanner's 8 or 12: drawn over 0 to
// 65,535 such a cloud was nearly black. The range is the 1st to the 99th percentile of a sample
// of the cloud's shallowest nodes (inner nodes hold the whole cloud, subsampled), as viewers such
// as CloudCompare stretch a scalar field over its values.

#include <cstddef>

namespace plumb::lod {
class NodeCache;
}

namespace plumb::render {

struct IntensityRange {
  float min = 0.0f;
  float max = 65535.0f;
};

// Reads nodes in the octree's order (shallowest first, through `nodes`, blocking) until
// `sample_points` points are seen. The full range [0, 65535] when the sample has no spread (one
// value, no points) or a node cannot be read (the frame that draws it reports that). Cost: the
// few nodes of the first levels, which the first frame draws anyway.
IntensityRange sampleIntensityRange(lod::NodeCache& nodes, std::size_t sample_points = 20'000);

}  // namespace plumb::render
