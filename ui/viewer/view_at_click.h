#pragma once
// The view a click was made in (reco::ViewAtClick, what the automatic parameters read) from a
// camera: `plumb grow --camera`, the viewer's Grow tool and its headless demo share it.

#include <Eigen/Core>
#include <optional>

#include "engine/view/camera.h"
#include "reco/parameters.h"

namespace plumb::viewer {

// The camera's matrices, the screen the user sees (`screen_width_px` x `screen_height_px`; the
// camera's viewport when 0) and the picked point. Nothing when `picked` lies behind the eye.
std::optional<reco::ViewAtClick> viewAtClick(const view::Camera& camera, const Eigen::Vector3d& picked,
                                             double screen_width_px = 0.0, double screen_height_px = 0.0);

}  // namespace plumb::viewer
