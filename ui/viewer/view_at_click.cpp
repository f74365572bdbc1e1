#include "ui/viewer/view_at_click.h"

#include <Eigen/Geometry>

namespace plumb::viewer {

std::optional<reco::ViewAtClick> viewAtClick(const view::Camera& camera, const Eigen::Vector3d& picked,
                                             double screen_width_px, double screen_height_px) {
  reco::ViewAtClick view;
  view.view = view::viewMatrix(camera);
  view.projection = view::projectionMatrix(camera);
  view.viewport_width_px = screen_width_px > 0.0 ? screen_width_px : camera.viewport_width_px;
  view.viewport_height_px = screen_height_px > 0.0 ? screen_height_px : camera.viewport_height_px;
  view.picked = picked;
  if ((view.view * picked.homogeneous()).z() >= 0.0) return std::nullopt;  // the camera looks down -z
  return view;
}

}  // namespace plumb::viewer
