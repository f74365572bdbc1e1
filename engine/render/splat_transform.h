#pragma once
// The transform the splat applies to points stored relative to an origin (a node's corner): to
// pixels (x right, y down, times w) and to the view depth. Made in double precision relative to
// the eye and only then rounded to float, so that a cloud in UTM coordinates keeps its
// millimetres on the GPU.

#include <Eigen/Core>
#include <array>

namespace plumb::view {
struct Camera;
}

namespace plumb::render {

struct SplatTransform {
  Eigen::Matrix4f clip_from_origin;  // column-major, as the shaders read it
  Eigen::Vector4f depth_from_origin;
};

// The camera must be valid; its viewport gives the pixel size.
SplatTransform splatTransform(const view::Camera& camera, const std::array<double, 3>& origin);

}  // namespace plumb::render
