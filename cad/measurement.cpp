#include "cad/measurement.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "cad/polygon_mesh.h"
#include "cad/project_validation.h"

namespace plumb::cad {
namespace {

using TermKind = MeasureTerm::Kind;

constexpr double kDegreesPerRadian = 180.0 / std::numbers::pi;

constexpr std::array<MeasureKind, 6> kKinds{MeasureKind::kDistance,     MeasureKind::kAngle,
                                            MeasureKind::kPointToPlane, MeasureKind::kBetweenPlanes,
                                            MeasureKind::kHeight,       MeasureKind::kArea};
constexpr std::array<TermKind, 4> kTermKinds{TermKind::kPoint, TermKind::kPlane, TermKind::kLine, TermKind::kPolygon};

// The acute angle between two undirected unit vectors, in radians: atan2 keeps its precision near
// 0 and 90 degrees, where acos and asin lose it.
double acuteAngle(const Eigen::Vector3d& u, const Eigen::Vector3d& v) {
  return std::atan2(u.cross(v).norm(), std::abs(u.dot(v)));
}

// The angle between two terms, each a plane (its normal) or a line (its direction).
double angleBetween(const MeasureTerm& a, const MeasureTerm& b) {
  const double between = acuteAngle(a.direction, b.direction);
  // A line and a plane: the line's angle to the plane is the complement of its angle to the normal.
  return a.kind == b.kind ? between : 0.5 * std::numbers::pi - between;
}

// The mean of two near-parallel unit normals, the second turned to agree with the first.
Eigen::Vector3d meanNormal(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return (a + (a.dot(b) < 0.0 ? -b : b)).normalized();
}

std::string degreesText(double degrees) {
  char text[32];
  std::snprintf(text, sizeof text, "%.2f\u00b0", degrees);
  return text;
}

std::string metresText(double metres) {
  char text[32];
  std::snprintf(text, sizeof text, "%.4f m", metres);
  return text;
}

std::optional<std::string> termProblem(const MeasureTerm& term, std::size_t index) {
  const std::string which = "term " + std::to_string(index + 1) + " (" + measureTermKindName(term.kind) + ")";
  if (!term.point.allFinite() || !term.direction.allFinite()) return which + ": a coordinate is not finite";
  switch (term.kind) {
    case TermKind::kPlane:
    case TermKind::kLine:
      if (std::abs(term.direction.norm() - 1.0) > kUnitTolerance) {
        return which + ": its direction must be a unit vector, but its length is " +
               std::to_string(term.direction.norm());
      }
      break;
    case TermKind::kPolygon:
      if (const auto problem = findPolygonProblem(term.ring)) return which + ": " + *problem;
      break;
    case TermKind::kPoint:
      break;
  }
  return std::nullopt;
}

}  // namespace

std::vector<std::vector<TermKind>> measureTermKinds(MeasureKind kind) {
  switch (kind) {
    case MeasureKind::kDistance:
      return {{TermKind::kPoint}, {TermKind::kPoint}};
    case MeasureKind::kAngle:
      return {{TermKind::kPlane, TermKind::kLine}, {TermKind::kPlane, TermKind::kLine}};
    case MeasureKind::kPointToPlane:
    case MeasureKind::kHeight:
      return {{TermKind::kPlane}, {TermKind::kPoint}};
    case MeasureKind::kBetweenPlanes:
      return {{TermKind::kPlane}, {TermKind::kPlane}};
    case MeasureKind::kArea:
      return {{TermKind::kPolygon}};
  }
  return {};
}

std::optional<std::string> measureProblem(MeasureKind kind, const std::vector<MeasureTerm>& terms) {
  const std::vector<std::vector<TermKind>> wanted = measureTermKinds(kind);
  if (terms.size() != wanted.size()) {
    return std::string(measureKindTitle(kind)) + " takes " + std::to_string(wanted.size()) + " term" +
           (wanted.size() == 1 ? "" : "s") + ", not " + std::to_string(terms.size());
  }
  for (std::size_t i = 0; i < terms.size(); ++i) {
    if (std::find(wanted[i].begin(), wanted[i].end(), terms[i].kind) == wanted[i].end()) {
      std::string accepted;
      for (const TermKind k : wanted[i])
        accepted += (accepted.empty() ? "" : " or ") + std::string(measureTermKindName(k));
      return std::string(measureKindTitle(kind)) + ": term " + std::to_string(i + 1) + " must be a " + accepted +
             ", not a " + measureTermKindName(terms[i].kind);
    }
    if (auto problem = termProblem(terms[i], i)) return problem;
  }
  if (kind == MeasureKind::kBetweenPlanes) {
    const double apart_deg = acuteAngle(terms[0].direction, terms[1].direction) * kDegreesPerRadian;
    if (apart_deg > kMaxParallelDeg) {
      return "the planes are " + degreesText(apart_deg) + " from parallel (at most " + degreesText(kMaxParallelDeg) +
             "): measure their angle instead";
    }
  }
  if (kind == MeasureKind::kHeight) {
    const double tilt_deg = acuteAngle(terms[0].direction, Eigen::Vector3d::UnitZ()) * kDegreesPerRadian;
    if (tilt_deg > kMaxFloorTiltDeg) {
      return "the floor is tilted " + degreesText(tilt_deg) + " from level (at most " + degreesText(kMaxFloorTiltDeg) +
             "): measure the distance to the plane instead";
    }
  }
  return std::nullopt;
}

MeasureValue measure(MeasureKind kind, const std::vector<MeasureTerm>& terms) {
  assert(!measureProblem(kind, terms));
  MeasureValue out;
  switch (kind) {
    case MeasureKind::kDistance:
      out.from = terms[0].point;
      out.to = terms[1].point;
      out.value = (out.to - out.from).norm();
      break;
    case MeasureKind::kAngle:
      out.from = terms[0].point;
      out.to = terms[1].point;
      out.value = angleBetween(terms[0], terms[1]) * kDegreesPerRadian;
      break;
    case MeasureKind::kPointToPlane: {
      const MeasureTerm& plane = terms[0];
      const double signed_distance = plane.direction.dot(terms[1].point - plane.point);
      out.from = terms[1].point;
      out.to = terms[1].point - signed_distance * plane.direction;  // the foot on the plane
      out.value = std::abs(signed_distance);
      break;
    }
    case MeasureKind::kBetweenPlanes: {
      // Along the mean normal through the middle of the picked points, from plane to plane.
      const MeasureTerm& a = terms[0];
      const MeasureTerm& b = terms[1];
      const Eigen::Vector3d normal = meanNormal(a.direction, b.direction);
      const Eigen::Vector3d middle = 0.5 * (a.point + b.point);
      const auto onPlane = [&](const MeasureTerm& plane) {
        return middle + (plane.direction.dot(plane.point - middle) / plane.direction.dot(normal)) * normal;
      };
      out.from = onPlane(a);
      out.to = onPlane(b);
      out.value = (out.to - out.from).norm();
      out.second = acuteAngle(a.direction, b.direction) * kDegreesPerRadian;
      break;
    }
    case MeasureKind::kHeight: {
      const MeasureTerm& floor = terms[0];
      const Eigen::Vector3d& p = terms[1].point;
      const Eigen::Vector3d& n = floor.direction;
      // The floor's plane under p: n . (x - q) = 0 solved for z at p's x and y.
      const double floor_z =
          floor.point.z() - (n.x() * (p.x() - floor.point.x()) + n.y() * (p.y() - floor.point.y())) / n.z();
      out.from = Eigen::Vector3d(p.x(), p.y(), floor_z);
      out.to = p;
      out.value = p.z() - floor_z;
      break;
    }
    case MeasureKind::kArea: {
      const std::vector<Eigen::Vector3d>& ring = terms[0].ring;
      Eigen::Vector3d twice_area = Eigen::Vector3d::Zero();
      Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
      double perimeter = 0.0;
      // Relative to the first vertex, so UTM coordinates keep their digits.
      for (std::size_t i = 0; i < ring.size(); ++i) {
        const Eigen::Vector3d a = ring[i] - ring[0];
        const Eigen::Vector3d b = ring[(i + 1) % ring.size()] - ring[0];
        twice_area += a.cross(b);
        perimeter += (b - a).norm();
        centroid += a;
      }
      out.value = 0.5 * twice_area.norm();  // the ring is planar: the Newell sum is twice its area along its normal
      out.second = perimeter;
      out.from = out.to = ring[0] + centroid / static_cast<double>(ring.size());
      break;
    }
  }
  return out;
}

const char* measureKindName(MeasureKind kind) {
  switch (kind) {
    case MeasureKind::kDistance:
      return "distance";
    case MeasureKind::kAngle:
      return "angle";
    case MeasureKind::kPointToPlane:
      return "point_to_plane";
    case MeasureKind::kBetweenPlanes:
      return "between_planes";
    case MeasureKind::kHeight:
      return "height";
    case MeasureKind::kArea:
      return "area";
  }
  return "";
}

std::optional<MeasureKind> measureKindNamed(std::string_view name) {
  for (const MeasureKind kind : kKinds) {
    if (name == measureKindName(kind)) return kind;
  }
  return std::nullopt;
}

const char* measureKindTitle(MeasureKind kind) {
  switch (kind) {
    case MeasureKind::kDistance:
      return "Distance";
    case MeasureKind::kAngle:
      return "Angle";
    case MeasureKind::kPointToPlane:
      return "Point to plane";
    case MeasureKind::kBetweenPlanes:
      return "Between planes";
    case MeasureKind::kHeight:
      return "Height";
    case MeasureKind::kArea:
      return "Area";
  }
  return "";
}

const char* measureUnit(MeasureKind kind) {
  switch (kind) {
    case MeasureKind::kAngle:
      return "deg";
    case MeasureKind::kArea:
      return "m2";
    default:
      return "m";
  }
}

std::string measureText(MeasureKind kind, const MeasureValue& value) {
  char text[96];
  switch (kind) {
    case MeasureKind::kAngle:
      return degreesText(value.value);
    case MeasureKind::kArea:
      std::snprintf(text, sizeof text, "%.3f m\u00b2 (perimeter %.3f m)", value.value, value.second.value_or(0.0));
      return text;
    case MeasureKind::kBetweenPlanes:
      return metresText(value.value) + " (" + degreesText(value.second.value_or(0.0)) + " from parallel)";
    default:
      return metresText(value.value);
  }
}

const char* measureTermKindName(MeasureTerm::Kind kind) {
  switch (kind) {
    case TermKind::kPoint:
      return "point";
    case TermKind::kPlane:
      return "plane";
    case TermKind::kLine:
      return "line";
    case TermKind::kPolygon:
      return "polygon";
  }
  return "";
}

std::optional<MeasureTerm::Kind> measureTermKindNamed(std::string_view name) {
  for (const TermKind kind : kTermKinds) {
    if (name == measureTermKindName(kind)) return kind;
  }
  return std::nullopt;
}

}  // namespace plumb::cad
