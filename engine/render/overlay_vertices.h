#pragma once
// The overlay scene as the vertices the overlay shaders draw: positions relative to the eye (the
// large world coordinates cancel in double precision before the rounding to float), two
// triangles per line and per marker.

#include <Eigen/Core>
#include <vector>

#include "engine/render/overlay_scene.h"
#include "shaders/render_layout.h"

namespace plumb::render {

std::vector<shader::OverlayVertex> overlayVertices(const OverlayScene& scene, const Eigen::Vector3d& eye);

}  // namespace plumb::render
