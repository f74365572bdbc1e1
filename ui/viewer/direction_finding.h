#pragma once
// Direction finding (paper section 4.2): what direction the pointer selects, and how a locked
// direction constrains a point.
//
//   pointing at a plane          its normal, turned towards the eye
//   pointing near an edge        its line, signed along the pointer's movement
//   pointing at a corner         the one of its three edge lines (the cross products of its
//                                segments' normals) that the pointer's movement follows most closely
//   pointing at a polygon vertex the one of its two sides, its normal and a prism's extrusion
//                                that the pointer's movement follows most closely
//
// "Follows most closely" compares the movement on screen with each candidate's image on screen
// at the feature, so a small flick of the mouse along an edge picks that edge.

#include <Eigen/Core>
#include <optional>

#include "engine/view/camera_controls.h"
#include "ui/viewer/components.h"
#include "ui/viewer/snapping.h"

namespace plumb::ecs {
class Registry;
}

namespace plumb::viewer {

// The direction the pointer at `snap` selects, `motion_px` its latest movement on screen
// (render pixels; zero: the candidate drawn longest on screen). Nothing for a point of the cloud.
std::optional<Direction> findDirection(const ecs::Registry& registry, const view::Camera& camera, const Snap& snap,
                                       const Eigen::Vector2d& motion_px);

// The point of the line origin + t direction (unit) that the pointer means: for a corner, vertex,
// edge or point snap its projection onto the line; for a plane snap where the line meets that
// plane (the projection when they are nearly parallel); with no snap the line's point nearest
// the pointer's ray. Nothing when the pointer's ray runs along the line.
std::optional<Eigen::Vector3d> constrainToLine(const ecs::Registry& registry, const Eigen::Vector3d& origin,
                                               const Eigen::Vector3d& direction, const std::optional<Snap>& snap,
                                               const view::Ray& ray);

}  // namespace plumb::viewer
