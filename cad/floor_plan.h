#pragma once
// A floor plan from the grown walls (issue 22, point 3): the section of a project's vertical
// segments by a horizontal plane. Where the other tools cut points, this cuts planes, so its
// lines are as precise as the planes the grower fitted.
//
// 1. Every segment whose normal is within max_tilt_deg of horizontal is a wall face; the section
//    plane z = height cuts its plane in a line.
// 2. The line is clipped to the segment's outline (the regression polygon, paper section 3.6):
//    the stretches inside it, by the even-odd rule over its rings. Gaps narrower than
//    min_opening_m are closed (scan shadows, sparse points); wider ones are openings (a door or a
//    window cut by the section).
// 3. Two parallel faces min_thickness_m to max_thickness_m apart whose stretches overlap are the
//    two faces of one wall, of the thickness measured between their planes. No other face runs
//    through a wall: the stretch of a face between a wall's two faces is cut out (the grower may
//    carry a face past a partition's end, into the next room, when the rooms' walls are coplanar).
// 4. Faces meet at corners: where the lines of two faces that are not parallel cross within
//    join_gap_m of an end of each, both ends move to the crossing, the intersection of the two
//    wall planes, nearest pairs first. So the plan closes where the points stop short of a
//    corner, as the planes do. An end near the middle of another face's stretch (an inner wall
//    meeting an outer one) moves onto that face's line. Then an outer end still free, short of
//    a crossing by up to join_reach_m, moves to it when the other face has a free end there and no
//    other face's stretch lies across the gap (a wall the grower stopped metres short of a
//    corner, seen at grazing angles).
//
// The result's lines are chained at shared ends into polylines; a chain that returns to its start
// is closed (a room's outline when every wall of it was grown).

#include <Eigen/Core>
#include <cstddef>
#include <string>
#include <vector>

#include "cad/project.h"

namespace plumb::cad {

struct FloorPlanOptions {
  double height_m = 0.0;       // world z of the section plane
  double max_tilt_deg = 5.0;   // a segment is a wall face when its normal is this close to horizontal
  double min_opening_m = 0.3;  // narrower gaps in a face's outline are closed
  double min_line_m = 0.02;    // shorter stretches are dropped
  double join_gap_m = 1.0;     // the most an end moves to meet another face's at their crossing
  // ... and the most an outer end moves to a corner when nothing lies across the gap
  double join_reach_m = 3.0;
  double min_join_angle_deg = 20.0;  // faces closer to parallel do not join
  double min_thickness_m = 0.03;     // two parallel faces this far apart, or farther, ...
  double max_thickness_m = 0.6;      // ... up to this, are the two faces of one wall
};

// A stretch of a wall face cut by the section: world coordinates, z = the section's height.
struct PlanLine {
  ItemId segment = kNoItem;
  Eigen::Vector3d start = Eigen::Vector3d::Zero();
  Eigen::Vector3d end = Eigen::Vector3d::Zero();
};

// A gap of at least min_opening_m between two stretches of one face.
struct PlanOpening {
  ItemId segment = kNoItem;
  Eigen::Vector3d start = Eigen::Vector3d::Zero();
  Eigen::Vector3d end = Eigen::Vector3d::Zero();
  double width_m = 0.0;
};

// The two faces of one wall and the distance between their planes.
struct PlanWall {
  ItemId face_a = kNoItem;
  ItemId face_b = kNoItem;
  double thickness_m = 0.0;
};

// Lines joined end to end; `closed` when the last joins the first.
struct PlanChain {
  std::vector<Eigen::Vector3d> vertices;
  bool closed = false;
};

struct FloorPlan {
  double height_m = 0.0;
  std::size_t wall_faces = 0;  // segments cut by the section
  std::vector<PlanLine> lines;
  std::vector<PlanOpening> openings;
  std::vector<PlanWall> walls;
  std::vector<PlanChain> chains;
  std::size_t joins = 0;  // corners where two faces' ends met
};

// The section of `project`'s wall faces at options.height_m. Segments without an outline are
// skipped (nothing says where they end). Deterministic: the same project gives the same plan.
FloorPlan floorPlanAt(const Project& project, const FloorPlanOptions& options);

// The plan as a 2D DXF drawing (R2000, cad/dxf_document.h), in metres: the chains as LWPOLYLINEs
// on layer PLAN_WALLS and the openings as open LWPOLYLINEs on PLAN_OPENINGS, all at the section's
// height (their elevation, group 38).
std::string floorPlanDxf(const FloorPlan& plan);

// The plan as SVG, drawn to scale: 1 user unit = 1 mm, x east, y north (flipped for SVG's y
// down), the walls black, the openings dashed, the section's height in the title and a caption.
std::string floorPlanSvg(const FloorPlan& plan);

}  // namespace plumb::cad
