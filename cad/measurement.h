#pragma once
// The values of measurements (cad/project.h, Measurement): what each kind asks for, what it gives,
// and how it reads. The value is computed from the terms every time (never stored), so the view,
// the panel, the project file and the CSV export cannot disagree.
//
// Conventions a surveyor expects:
// - an angle between planes or lines is the acute one, 0 to 90 degrees (a plane's normal and a
//   line's direction have no meaningful sign: the grower's normals point either way);
// - the distance between two planes is measured along their mean normal at the middle of the two
//   picked points (exact for parallel planes; for planes a little off parallel, the width there);
// - a height is vertical (along world z) from the floor's plane under the point, signed: below
//   the floor is negative.

#include <Eigen/Core>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "cad/project.h"

namespace plumb::cad {

// Two planes further from parallel than this have no distance apart (measure their angle).
inline constexpr double kMaxParallelDeg = 5.0;
// A plane tilted further from level than this is no floor to measure heights from.
inline constexpr double kMaxFloorTiltDeg = 30.0;

struct MeasureValue {
  double value = 0.0;  // in measureUnit(kind): metres, degrees or square metres
  // kArea: the perimeter (m). kBetweenPlanes: the angle between the planes (degrees). Else none.
  std::optional<double> second;
  // The dimension line the view draws and labels: between the two things measured (kDistance,
  // kPointToPlane, kBetweenPlanes, kHeight), between the two picked points (kAngle), or the
  // polygon's centroid twice (kArea).
  Eigen::Vector3d from = Eigen::Vector3d::Zero();
  Eigen::Vector3d to = Eigen::Vector3d::Zero();
};

// The term kinds `kind` takes, in order: each entry lists the kinds accepted at that place.
std::vector<std::vector<MeasureTerm::Kind>> measureTermKinds(MeasureKind kind);

// Why `terms` cannot be measured as `kind`, as a sentence, or nothing: the wrong number or kind
// of terms, a coordinate not finite, a direction not of unit length, a polygon that is not one,
// planes too far from parallel (kBetweenPlanes), a floor too steep (kHeight).
std::optional<std::string> measureProblem(MeasureKind kind, const std::vector<MeasureTerm>& terms);

// The value of `terms` measured as `kind`; measureProblem must find nothing (asserted).
MeasureValue measure(MeasureKind kind, const std::vector<MeasureTerm>& terms);

// "distance", "angle", "point_to_plane", "between_planes", "height", "area": the names of the
// project file, the CSV export, session scripts and the scene dump.
const char* measureKindName(MeasureKind kind);
std::optional<MeasureKind> measureKindNamed(std::string_view name);
// "Distance", "Angle", "Point to plane", "Between planes", "Height", "Area": what people read.
const char* measureKindTitle(MeasureKind kind);
// "m", "deg", "m2".
const char* measureUnit(MeasureKind kind);
// The value as the view and the panel show it: "3.2051 m", "89.98°", "12.304 m² (perimeter
// 14.201 m)", "2.5003 m (0.02° from parallel)". Millimetres shown, as a tape gives them.
std::string measureText(MeasureKind kind, const MeasureValue& value);

const char* measureTermKindName(MeasureTerm::Kind kind);  // "point", "plane", "line", "polygon"
std::optional<MeasureTerm::Kind> measureTermKindNamed(std::string_view name);

}  // namespace plumb::cad
