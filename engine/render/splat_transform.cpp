#include "engine/render/splat_transform.h"

#include "engine/view/camera.h"

namespace plumb::render {

SplatTransform splatTransform(const view::Camera& camera, const std::array<double, 3>& origin) {
  const Eigen::Matrix4d view = view::viewMatrix(camera);
  Eigen::Matrix4d pixel_from_ndc = Eigen::Matrix4d::Identity();
  pixel_from_ndc(0, 0) = 0.5 * camera.viewport_width_px;
  pixel_from_ndc(0, 3) = 0.5 * camera.viewport_width_px;
  pixel_from_ndc(1, 1) = -0.5 * camera.viewport_height_px;
  pixel_from_ndc(1, 3) = 0.5 * camera.viewport_height_px;
  // view * translate(origin) = [R | R (origin - eye)]: the large terms cancel in double.
  const Eigen::Vector3d from_eye = Eigen::Vector3d(origin[0], origin[1], origin[2]) - camera.position;
  Eigen::Matrix4d view_from_origin = view;
  view_from_origin.block<3, 1>(0, 3) = view.block<3, 3>(0, 0) * from_eye;
  return {(pixel_from_ndc * view::projectionMatrix(camera) * view_from_origin).cast<float>(),
          (-view_from_origin.row(2)).transpose().cast<float>()};
}

}  // namespace plumb::render
