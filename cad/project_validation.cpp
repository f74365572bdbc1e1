#include "cad/project_validation.h"

#include <cmath>
#include <unordered_map>

#include "cad/measurement.h"
#include "cad/polygon_mesh.h"
#include "engine/core/error.h"

namespace plumb::cad {
namespace {

enum class Kind { kGroup, kSegment, kEdge, kCorner, kPolygon, kMeasurement };

const char* kindName(Kind kind) {
  switch (kind) {
    case Kind::kGroup:
      return "group";
    case Kind::kSegment:
      return "segment";
    case Kind::kEdge:
      return "edge";
    case Kind::kCorner:
      return "corner";
    case Kind::kPolygon:
      return "polygon";
    case Kind::kMeasurement:
      return "measurement";
  }
  return "item";
}

std::string at(const char* list, std::size_t index, const std::string& field) {
  return std::string(list) + "[" + std::to_string(index) + "]" + (field.empty() ? "" : "." + field);
}

// Checks in order; `problem` keeps the first one found.
class Checker {
 public:
  explicit Checker(const Project& project) : project_(project) {}

  std::optional<ProjectProblem> run() {
    if (project_.camera) {
      if (const auto camera = findCameraProblem(*project_.camera)) {
        return ProjectProblem{"camera." + camera->field, camera->what};
      }
    }
    for (std::size_t i = 0; i < project_.groups.size(); ++i) addId("groups", i, project_.groups[i].id, Kind::kGroup);
    for (std::size_t i = 0; i < project_.segments.size(); ++i) {
      addId("segments", i, project_.segments[i].id, Kind::kSegment);
    }
    for (std::size_t i = 0; i < project_.edges.size(); ++i) addId("edges", i, project_.edges[i].id, Kind::kEdge);
    for (std::size_t i = 0; i < project_.corners.size(); ++i) {
      addId("corners", i, project_.corners[i].id, Kind::kCorner);
    }
    for (std::size_t i = 0; i < project_.polygons.size(); ++i) {
      addId("polygons", i, project_.polygons[i].id, Kind::kPolygon);
    }
    for (std::size_t i = 0; i < project_.measurements.size(); ++i) {
      addId("measurements", i, project_.measurements[i].id, Kind::kMeasurement);
    }
    if (problem_) return problem_;

    for (std::size_t i = 0; i < project_.segments.size(); ++i) checkSegment(i);
    for (std::size_t i = 0; i < project_.edges.size(); ++i) checkEdge(i);
    for (std::size_t i = 0; i < project_.corners.size(); ++i) checkCorner(i);
    for (std::size_t i = 0; i < project_.polygons.size(); ++i) checkPolygon(i);
    for (std::size_t i = 0; i < project_.measurements.size(); ++i) checkMeasurement(i);
    return problem_;
  }

 private:
  void fail(std::string place, std::string what) {
    if (!problem_) problem_ = ProjectProblem{std::move(place), std::move(what)};
  }

  void addId(const char* list, std::size_t index, ItemId id, Kind kind) {
    const std::string place = at(list, index, "id");
    if (id == kNoItem) return fail(place, "an id must be positive (0 means \"none\")");
    const auto [it, inserted] = items_.try_emplace(id, Item{kind, at(list, index, "")});
    if (!inserted) fail(place, "id " + std::to_string(id) + " is already the id of " + it->second.place);
  }

  void reference(const std::string& place, ItemId id, Kind kind) {
    if (id == kNoItem) return;
    const auto it = items_.find(id);
    if (it == items_.end()) {
      return fail(place, "refers to id " + std::to_string(id) + ", which no item of the project has");
    }
    if (it->second.kind != kind) {
      fail(place, "refers to id " + std::to_string(id) + ", which is a " + kindName(it->second.kind) + " (" +
                      it->second.place + "), not a " + kindName(kind));
    }
  }

  void finite(const std::string& place, double value) {
    if (!std::isfinite(value)) fail(place, "the number is not finite");
  }
  template <typename Vector>
  void finite(const std::string& place, const Vector& value) {
    if (!value.allFinite()) fail(place, "a coordinate is not finite");
  }
  void unit(const std::string& place, const Eigen::Vector3d& direction) {
    finite(place, direction);
    if (std::isfinite(direction.norm()) && std::abs(direction.norm() - 1.0) > kUnitTolerance) {
      fail(place, "must be a unit vector, but its length is " + std::to_string(direction.norm()));
    }
  }

  void checkSegment(std::size_t i) {
    const Segment& segment = project_.segments[i];
    reference(at("segments", i, "group"), segment.group, Kind::kGroup);
    const reco::Plane& plane = segment.plane;
    const std::string p = at("segments", i, "plane");
    if (!plane.valid) fail(p, "the plane is not valid (a degenerate regression); delete the segment");
    unit(p + ".normal", plane.normal);
    unit(p + ".tangent", plane.tangent);
    unit(p + ".bitangent", plane.bitangent);
    finite(p + ".centroid", plane.centroid);
    finite(p + ".offset", plane.offset);
    finite(p + ".lambda0", plane.lambda0);
    finite(p + ".lambda1", plane.lambda1);
    finite(p + ".lambda2", plane.lambda2);
    finite(p + ".rms", plane.rms);

    const reco::PlaneOutline& outline = segment.outline;
    const std::string o = at("segments", i, "outline");
    finite(o + ".origin", outline.origin);
    unit(o + ".axis_u", outline.axis_u);
    unit(o + ".axis_v", outline.axis_v);
    if (std::abs(outline.axis_u.dot(outline.axis_v)) > kUnitTolerance) {
      fail(o + ".axis_v", "must be perpendicular to axis_u");
    }
    for (std::size_t r = 0; r < outline.shape.rings.size(); ++r) {
      for (std::size_t v = 0; v < outline.shape.rings[r].size(); ++v) {
        finite(o + ".rings[" + std::to_string(r) + "][" + std::to_string(v) + "]", outline.shape.rings[r][v]);
      }
    }
    for (std::size_t v = 0; v < outline.shape.vertices.size(); ++v) {
      finite(o + ".vertices[" + std::to_string(v) + "]", outline.shape.vertices[v]);
    }
    for (std::size_t t = 0; t < outline.shape.triangles.size(); ++t) {
      for (std::size_t k = 0; k < 3; ++k) {
        const std::uint32_t index = outline.shape.triangles[t][k];
        if (index >= outline.shape.vertices.size()) {
          fail(o + ".triangles[" + std::to_string(t) + "][" + std::to_string(k) + "]",
               "vertex " + std::to_string(index) + " does not exist: the outline has " +
                   std::to_string(outline.shape.vertices.size()) + " vertices");
        }
      }
    }
    finite(o + ".area_m2", outline.shape.area_m2);
    finite(o + ".cell_m", outline.shape.cell_m);
  }

  void checkEdge(std::size_t i) {
    const Edge& edge = project_.edges[i];
    reference(at("edges", i, "group"), edge.group, Kind::kGroup);
    for (std::size_t k = 0; k < edge.segments.size(); ++k) {
      reference(at("edges", i, "segments[" + std::to_string(k) + "]"), edge.segments[k], Kind::kSegment);
    }
    finite(at("edges", i, "start"), edge.start);
    finite(at("edges", i, "end"), edge.end);
  }

  void checkCorner(std::size_t i) {
    const Corner& corner = project_.corners[i];
    reference(at("corners", i, "group"), corner.group, Kind::kGroup);
    for (std::size_t k = 0; k < corner.segments.size(); ++k) {
      reference(at("corners", i, "segments[" + std::to_string(k) + "]"), corner.segments[k], Kind::kSegment);
    }
    finite(at("corners", i, "position"), corner.position);
    for (std::size_t k = 0; k < corner.support.size(); ++k) {
      finite(at("corners", i, "support[" + std::to_string(k) + "]"), corner.support[k]);
    }
  }

  void checkPolygon(std::size_t i) {
    const Polygon& polygon = project_.polygons[i];
    reference(at("polygons", i, "group"), polygon.group, Kind::kGroup);
    reference(at("polygons", i, "plane"), polygon.plane, Kind::kSegment);
    if (const auto ring = findPolygonProblem(polygon.vertices)) return fail(at("polygons", i, "vertices"), *ring);
    finite(at("polygons", i, "extrusion"), polygon.extrusion);
    if (polygon.isPrism() && polygon.extrusion.allFinite() &&
        std::abs(polygonNormal(polygon.vertices).dot(polygon.extrusion)) < kPolygonResolution) {
      fail(at("polygons", i, "extrusion"),
           "the extrusion lies in the polygon's plane: a prism needs a height along the polygon's normal");
    }
  }

  void checkMeasurement(std::size_t i) {
    const Measurement& measurement = project_.measurements[i];
    reference(at("measurements", i, "group"), measurement.group, Kind::kGroup);
    if (const auto problem = measureProblem(measurement.kind, measurement.terms)) {
      return fail(at("measurements", i, "terms"), *problem);
    }
    if (measurement.sources.size() != measurement.terms.size()) {
      return fail(at("measurements", i, "sources"),
                  "must name one item (or 0) per term: " + std::to_string(measurement.terms.size()) + " terms, " +
                      std::to_string(measurement.sources.size()) + " sources");
    }
    // A term is taken on a segment, an edge, a corner or a polygon; never on a group or another
    // measurement.
    for (std::size_t k = 0; k < measurement.sources.size(); ++k) {
      const ItemId id = measurement.sources[k];
      const std::string place = at("measurements", i, "sources[" + std::to_string(k) + "]");
      const auto it = items_.find(id);
      if (id == kNoItem) continue;
      if (it == items_.end()) {
        fail(place, "refers to id " + std::to_string(id) + ", which no item of the project has");
      } else if (it->second.kind == Kind::kGroup || it->second.kind == Kind::kMeasurement) {
        fail(place, "refers to id " + std::to_string(id) + ", which is a " + kindName(it->second.kind) + " (" +
                        it->second.place + "): a measurement is taken on a segment, edge, corner or polygon");
      }
    }
  }

  struct Item {
    Kind kind;
    std::string place;
  };

  const Project& project_;
  std::unordered_map<ItemId, Item> items_;
  std::optional<ProjectProblem> problem_;
};

}  // namespace

std::optional<ProjectProblem> findProjectProblem(const Project& project) {
  return Checker(project).run();
}

void validateProject(const Project& project, const std::string& path, std::string_view refusal) {
  if (const auto problem = findProjectProblem(project)) {
    throw fileError(path, std::string(refusal) + ": field '" + problem->place + "': " + problem->what);
  }
}

}  // namespace plumb::cad
