#include "cad/floor_plan.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <numbers>
#include <optional>
#include <tuple>
#include <utility>

#include "cad/dxf_document.h"

namespace plumb::cad {
namespace {

double radians(double degrees) {
  return degrees * std::numbers::pi / 180.0;
}

double cross2(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return a.x() * b.y() - a.y() * b.x();
}

// `value` with `decimals` digits after the point, for SVG (no exponent, no locale).
std::string fixed(double value, int decimals) {
  char text[64];
  std::snprintf(text, sizeof text, "%.*f", decimals, value);
  return text;
}

// A wall face's line in the section plane: p(t) = origin + t direction, direction unit and
// horizontal, origin at the section's height.
struct FaceLine {
  const Segment* segment = nullptr;
  Eigen::Vector3d origin;
  Eigen::Vector3d direction;
  std::vector<std::pair<double, double>> stretches;  // [t0, t1], ascending, disjoint
};

std::optional<FaceLine> faceLine(const Segment& segment, const FloorPlanOptions& options) {
  const Eigen::Vector3d& n = segment.plane.normal;
  const Eigen::Vector3d horizontal(n.x(), n.y(), 0.0);
  if (horizontal.norm() < std::cos(radians(options.max_tilt_deg))) return std::nullopt;
  if (segment.outline.shape.rings.empty()) return std::nullopt;
  const Eigen::Vector3d& c = segment.plane.centroid;
  const double along = -n.z() * (options.height_m - c.z()) / horizontal.squaredNorm();
  FaceLine line;
  line.segment = &segment;
  line.origin = c + Eigen::Vector3d(0.0, 0.0, options.height_m - c.z()) + along * horizontal;
  line.direction = n.cross(Eigen::Vector3d::UnitZ()).normalized();
  return line;
}

// The stretches of the face's line inside its outline (step 2 of the header), and the openings
// between them.
void clipToOutline(FaceLine& line, const FloorPlanOptions& options, std::vector<PlanOpening>& openings) {
  const reco::PlaneOutline& outline = line.segment->outline;
  const Eigen::Vector2d a((line.origin - outline.origin).dot(outline.axis_u),
                          (line.origin - outline.origin).dot(outline.axis_v));
  const Eigen::Vector2d b(line.direction.dot(outline.axis_u), line.direction.dot(outline.axis_v));
  if (b.norm() < 1e-9) return;
  // Where the line crosses the rings' edges: a + t b = q1 + s (q2 - q1), s in [0, 1).
  std::vector<double> crossings;
  for (const auto& ring : outline.shape.rings) {
    for (std::size_t i = 0; i < ring.size(); ++i) {
      const Eigen::Vector2d& q1 = ring[i];
      const Eigen::Vector2d edge = ring[(i + 1) % ring.size()] - q1;
      const double denominator = cross2(b, edge);
      if (std::abs(denominator) < 1e-15) continue;
      const double s = cross2(b, a - q1) / denominator;
      if (s < 0.0 || s >= 1.0) continue;
      crossings.push_back(cross2(edge, a - q1) / denominator);
    }
  }
  std::sort(crossings.begin(), crossings.end());
  std::vector<std::pair<double, double>> inside;
  for (std::size_t i = 0; i + 1 < crossings.size(); ++i) {
    const double middle = 0.5 * (crossings[i] + crossings[i + 1]);
    if (crossings[i + 1] - crossings[i] <= 0.0 || !outline.shape.contains(a + middle * b)) continue;
    if (!inside.empty() && crossings[i] - inside.back().second < options.min_opening_m) {
      inside.back().second = crossings[i + 1];  // a gap narrower than an opening: closed
    } else {
      inside.emplace_back(crossings[i], crossings[i + 1]);
    }
  }
  for (const auto& stretch : inside) {
    if (stretch.second - stretch.first >= options.min_line_m) line.stretches.push_back(stretch);
  }
  for (std::size_t i = 0; i + 1 < line.stretches.size(); ++i) {
    const double from = line.stretches[i].second, to = line.stretches[i + 1].first;
    openings.push_back(
        {line.segment->id, line.origin + from * line.direction, line.origin + to * line.direction, to - from});
  }
}

// Where the lines of two faces cross, as the parameters along each; empty when near parallel.
std::optional<std::pair<double, double>> crossing(const FaceLine& a, const FaceLine& b, double min_angle_rad) {
  const Eigen::Vector2d da = a.direction.head<2>(), db = b.direction.head<2>();
  const double sine = cross2(da, db);
  if (std::abs(sine) < std::sin(min_angle_rad)) return std::nullopt;
  const Eigen::Vector2d offset = (b.origin - a.origin).head<2>();
  return std::pair{cross2(offset, db) / sine, cross2(offset, da) / sine};
}

// One end of one stretch: face f, stretch s, end 0 (start) or 1 (end).
struct EndRef {
  std::size_t face, stretch, end;
  double& parameter(std::vector<FaceLine>& faces) const {
    auto& s = faces[face].stretches[stretch];
    return end == 0 ? s.first : s.second;
  }
  double at(const std::vector<FaceLine>& faces) const {
    const auto& s = faces[face].stretches[stretch];
    return end == 0 ? s.first : s.second;
  }
};

// Whether the 2D segment from p to q crosses the stretch [t0, t1] of `face`.
bool crossesStretch(const Eigen::Vector2d& p, const Eigen::Vector2d& q, const FaceLine& face, double t0, double t1) {
  const Eigen::Vector2d a = (face.origin + t0 * face.direction).head<2>();
  const Eigen::Vector2d b = (face.origin + t1 * face.direction).head<2>();
  const double d1 = cross2(q - p, a - p), d2 = cross2(q - p, b - p);
  const double d3 = cross2(b - a, p - a), d4 = cross2(b - a, q - a);
  return ((d1 < 0.0) != (d2 < 0.0)) && ((d3 < 0.0) != (d4 < 0.0));
}

using EndKey = std::tuple<std::size_t, std::size_t, std::size_t>;

// How far a wall's stretch may run past a corner's crossing and still end there (its outline
// reaches into the other wall's noise).
constexpr double kCornerOvershoot = 0.1;  // metres

// Step 3, for what the join gap leaves open: a face's outer end, still free, that stops short of
// its line's crossing with another face by more than the join gap but at most join_reach_m moves
// to the crossing when the other face has a free end within the join gap of it (a corner, not a T)
// and no other face's stretch lies across the gap. So a corridor's long walls, grown only to
// metres short of its ends where the scanner saw them at grazing angles, still meet its end walls.
std::size_t joinAcrossEmptyGaps(std::vector<FaceLine>& faces, const FloorPlanOptions& options,
                                std::map<EndKey, bool>& moved) {
  struct Reach {
    double gap;
    EndRef far, near;
    double t_far, t_near;
  };
  std::vector<Reach> reaches;
  const double min_angle = radians(options.min_join_angle_deg);
  const auto key = [](const EndRef& e) { return EndKey{e.face, e.stretch, e.end}; };
  for (std::size_t i = 0; i < faces.size(); ++i) {
    if (faces[i].stretches.empty()) continue;
    // The face's two outer ends: its first stretch's start, its last one's end.
    for (const EndRef end : {EndRef{i, 0, 0}, EndRef{i, faces[i].stretches.size() - 1, 1}}) {
      if (moved[key(end)]) continue;
      for (std::size_t j = 0; j < faces.size(); ++j) {
        if (j == i) continue;
        const auto cross = crossing(faces[i], faces[j], min_angle);
        if (!cross) continue;
        const auto [ti, tj] = *cross;
        // Beyond the end, along the line's continuation.
        const double gap = end.end == 0 ? end.at(faces) - ti : ti - end.at(faces);
        if (gap <= options.join_gap_m || gap > options.join_reach_m) continue;
        // The other face's end nearest the crossing, within the join gap, with the crossing at or
        // beyond it (a corner; a crossing well inside its stretch is a T, or a wall across).
        std::optional<EndRef> near;
        for (std::size_t s = 0; s < faces[j].stretches.size(); ++s) {
          for (std::size_t e = 0; e < 2; ++e) {
            const EndRef other{j, s, e};
            const double off = std::abs(other.at(faces) - tj);
            const double inside = e == 0 ? tj - other.at(faces) : other.at(faces) - tj;
            if (moved[key(other)] || off > options.join_gap_m || inside > kCornerOvershoot) continue;
            if (!near || off < std::abs(near->at(faces) - tj)) near = other;
          }
        }
        if (!near) continue;
        const Eigen::Vector2d p = (faces[i].origin + end.at(faces) * faces[i].direction).head<2>();
        const Eigen::Vector2d q = (faces[i].origin + ti * faces[i].direction).head<2>();
        bool blocked = false;
        for (std::size_t k = 0; k < faces.size() && !blocked; ++k) {
          if (k == i || k == j) continue;
          for (const auto& [t0, t1] : faces[k].stretches) blocked = blocked || crossesStretch(p, q, faces[k], t0, t1);
        }
        if (!blocked) reaches.push_back({gap, end, *near, ti, tj});
      }
    }
  }
  std::stable_sort(reaches.begin(), reaches.end(), [](const Reach& x, const Reach& y) { return x.gap < y.gap; });
  std::size_t joins = 0;
  for (const Reach& r : reaches) {
    if (moved[key(r.far)] || moved[key(r.near)]) continue;
    r.far.parameter(faces) = r.t_far;
    r.near.parameter(faces) = r.t_near;
    moved[key(r.far)] = moved[key(r.near)] = true;
    ++joins;
  }
  return joins;
}

// Step 3 of the header: the ends of two faces that meet near their lines' crossing move to it,
// nearest pairs first; then an end near another face's stretch (a T: an inner wall meeting an
// outer one) moves onto that face's line. Returns the corners joined.
std::size_t joinCorners(std::vector<FaceLine>& faces, const FloorPlanOptions& options) {
  struct Candidate {
    double cost;
    EndRef a, b;
    double ta, tb;
  };
  std::vector<Candidate> candidates;
  struct Tee {
    double cost;  // how far the end moves
    EndRef end;
    double t;
  };
  std::vector<Tee> tees;
  const double min_angle = radians(options.min_join_angle_deg);
  for (std::size_t i = 0; i < faces.size(); ++i) {
    for (std::size_t j = i + 1; j < faces.size(); ++j) {
      const auto cross = crossing(faces[i], faces[j], min_angle);
      if (!cross) continue;
      const auto [ti, tj] = *cross;
      const auto near_ends = [&](std::size_t f, double t) {
        std::vector<EndRef> ends;
        for (std::size_t s = 0; s < faces[f].stretches.size(); ++s) {
          for (std::size_t e = 0; e < 2; ++e) {
            const EndRef end{f, s, e};
            if (std::abs(end.at(faces) - t) <= options.join_gap_m) ends.push_back(end);
          }
        }
        return ends;
      };
      const auto inside = [&](std::size_t f, double t) {
        for (const auto& [t0, t1] : faces[f].stretches) {
          if (t > t0 + options.join_gap_m && t < t1 - options.join_gap_m) return true;
        }
        return false;
      };
      const std::vector<EndRef> ends_i = near_ends(i, ti), ends_j = near_ends(j, tj);
      for (const EndRef& a : ends_i) {
        for (const EndRef& b : ends_j) {
          candidates.push_back({std::abs(a.at(faces) - ti) + std::abs(b.at(faces) - tj), a, b, ti, tj});
        }
      }
      if (inside(i, ti)) {
        for (const EndRef& b : ends_j) tees.push_back({std::abs(b.at(faces) - tj), b, tj});
      }
      if (inside(j, tj)) {
        for (const EndRef& a : ends_i) tees.push_back({std::abs(a.at(faces) - ti), a, ti});
      }
    }
  }
  std::stable_sort(candidates.begin(), candidates.end(),
                   [](const Candidate& x, const Candidate& y) { return x.cost < y.cost; });
  std::map<EndKey, bool> moved;
  const auto key = [](const EndRef& e) { return std::tuple{e.face, e.stretch, e.end}; };
  std::size_t joins = 0;
  for (const Candidate& c : candidates) {
    if (moved[key(c.a)] || moved[key(c.b)]) continue;
    c.a.parameter(faces) = c.ta;
    c.b.parameter(faces) = c.tb;
    moved[key(c.a)] = moved[key(c.b)] = true;
    ++joins;
  }
  std::stable_sort(tees.begin(), tees.end(), [](const Tee& x, const Tee& y) { return x.cost < y.cost; });
  for (const Tee& tee : tees) {
    if (moved[key(tee.end)]) continue;
    tee.end.parameter(faces) = tee.t;
    moved[key(tee.end)] = true;
  }
  joins += joinAcrossEmptyGaps(faces, options, moved);
  // A join may turn a stretch around (both its ends moved past each other): drop it.
  for (FaceLine& face : faces) {
    std::erase_if(face.stretches, [&](const auto& s) { return s.second - s.first < options.min_line_m; });
  }
  return joins;
}

// Step 4: parallel faces a wall's thickness apart whose stretches overlap.
std::vector<PlanWall> pairFaces(const std::vector<FaceLine>& faces, const FloorPlanOptions& options) {
  std::vector<PlanWall> walls;
  for (std::size_t i = 0; i < faces.size(); ++i) {
    for (std::size_t j = i + 1; j < faces.size(); ++j) {
      const FaceLine &a = faces[i], &b = faces[j];
      if (a.stretches.empty() || b.stretches.empty()) continue;
      if (std::abs(a.direction.dot(b.direction)) < std::cos(radians(2.0))) continue;
      const Eigen::Vector3d middle =
          a.origin + 0.5 * (a.stretches.front().first + a.stretches.back().second) * a.direction;
      const double thickness = b.segment->plane.distance(middle);
      if (thickness < options.min_thickness_m || thickness > options.max_thickness_m) continue;
      // b's extent along a's line.
      double b0 = std::numeric_limits<double>::infinity(), b1 = -b0;
      for (const auto& [t0, t1] : b.stretches) {
        for (const double t : {t0, t1}) {
          const double along = (b.origin + t * b.direction - a.origin).dot(a.direction);
          b0 = std::min(b0, along);
          b1 = std::max(b1, along);
        }
      }
      const double overlap = std::min(a.stretches.back().second, b1) - std::max(a.stretches.front().first, b0);
      if (overlap > options.min_opening_m) walls.push_back({a.segment->id, b.segment->id, thickness});
    }
  }
  return walls;
}

// Where face `f`'s line crosses the plane of `face`, as a parameter along f; empty when parallel.
std::optional<double> crossingPlane(const FaceLine& f, const Segment& face) {
  const double along = face.plane.normal.dot(f.direction);
  if (std::abs(along) < 1e-9) return std::nullopt;
  return -face.plane.signedDistance(f.origin) / along;
}

// No face runs through the inside of a wall: the stretch of a face between a wall's two faces,
// within the wall's length, is cut out. So a face that the grower carried on past a partition
// (coplanar walls of two rooms, joined across the partition's end) is split into its rooms, and
// each part meets its own room's walls.
void cutInsideWalls(std::vector<FaceLine>& faces, const std::vector<PlanWall>& walls, const FloorPlanOptions& options) {
  const auto face_of = [&](ItemId id) -> const FaceLine* {
    for (const FaceLine& face : faces) {
      if (face.segment->id == id) return &face;
    }
    return nullptr;
  };
  for (const PlanWall& wall : walls) {
    const FaceLine* a = face_of(wall.face_a);
    const FaceLine* b = face_of(wall.face_b);
    // The wall's length: along a's line, over both faces' stretches.
    double from = std::numeric_limits<double>::infinity(), to = -from;
    for (const FaceLine* side : {a, b}) {
      for (const auto& [t0, t1] : side->stretches) {
        for (const double t : {t0, t1}) {
          const double along = (side->origin + t * side->direction - a->origin).dot(a->direction);
          from = std::min(from, along);
          to = std::max(to, along);
        }
      }
    }
    for (FaceLine& face : faces) {
      if (&face == a || &face == b) continue;
      const auto ta = crossingPlane(face, *a->segment), tb = crossingPlane(face, *b->segment);
      if (!ta || !tb) continue;
      const double cut0 = std::min(*ta, *tb), cut1 = std::max(*ta, *tb);
      const double along = (face.origin + 0.5 * (cut0 + cut1) * face.direction - a->origin).dot(a->direction);
      // Beyond the wall's end the face passes it by; at the end (within its thickness: the points
      // stop short of a corner) the face runs into the solid where the wall meets it.
      if (along < from - wall.thickness_m || along > to + wall.thickness_m) continue;
      std::vector<std::pair<double, double>> kept;
      for (const auto& [t0, t1] : face.stretches) {
        if (t1 <= cut0 || t0 >= cut1) {
          kept.emplace_back(t0, t1);
          continue;
        }
        if (cut0 - t0 >= options.min_line_m) kept.emplace_back(t0, cut0);
        if (t1 - cut1 >= options.min_line_m) kept.emplace_back(cut1, t1);
      }
      face.stretches = std::move(kept);
    }
  }
}

// The lines chained at ends they share exactly (the joins put both ends on the same crossing).
std::vector<PlanChain> chainLines(const std::vector<PlanLine>& lines) {
  using Key = std::array<double, 3>;
  const auto key = [](const Eigen::Vector3d& p) { return Key{p.x(), p.y(), p.z()}; };
  std::map<Key, std::vector<std::size_t>> at;  // line ends at a point: 2 i + (0 start, 1 end)
  for (std::size_t i = 0; i < lines.size(); ++i) {
    at[key(lines[i].start)].push_back(2 * i);
    at[key(lines[i].end)].push_back(2 * i + 1);
  }
  std::vector<bool> used(lines.size(), false);
  const auto point = [&](std::size_t end) { return end % 2 == 0 ? lines[end / 2].start : lines[end / 2].end; };
  // The other line's end at the point of `end`, when exactly one other line ends there.
  const auto next = [&](std::size_t end) -> std::optional<std::size_t> {
    const auto& here = at[key(point(end))];
    if (here.size() != 2) return std::nullopt;
    const std::size_t other = here[0] == end ? here[1] : here[0];
    if (used[other / 2]) return std::nullopt;
    return other;
  };
  std::vector<PlanChain> chains;
  // Open chains first, from ends no other line shares; then what is left is closed loops.
  for (int pass = 0; pass < 2; ++pass) {
    for (std::size_t i = 0; i < lines.size(); ++i) {
      if (used[i]) continue;
      std::size_t start = 2 * i;
      if (pass == 0) {
        if (at[key(lines[i].start)].size() == 2 && at[key(lines[i].end)].size() == 2) continue;
        if (at[key(lines[i].start)].size() == 2) start = 2 * i + 1;  // begin at the free end
      }
      PlanChain chain;
      chain.vertices.push_back(point(start));
      std::size_t end = start;
      while (true) {
        used[end / 2] = true;
        const std::size_t far = end ^ 1u;
        chain.vertices.push_back(point(far));
        const auto following = next(far);
        if (!following) break;
        end = *following;
      }
      if (chain.vertices.size() > 2 && chain.vertices.back() == chain.vertices.front()) {
        chain.vertices.pop_back();
        chain.closed = true;
      }
      chains.push_back(std::move(chain));
    }
  }
  return chains;
}

}  // namespace

FloorPlan floorPlanAt(const Project& project, const FloorPlanOptions& options) {
  FloorPlan plan;
  plan.height_m = options.height_m;
  std::vector<FaceLine> faces;
  for (const Segment& segment : project.segments) {
    std::optional<FaceLine> line = faceLine(segment, options);
    if (!line) continue;
    clipToOutline(*line, options, plan.openings);
    if (line->stretches.empty()) continue;
    faces.push_back(std::move(*line));
  }
  plan.wall_faces = faces.size();
  plan.walls = pairFaces(faces, options);
  cutInsideWalls(faces, plan.walls, options);
  plan.joins = joinCorners(faces, options);
  for (const FaceLine& face : faces) {
    for (const auto& [t0, t1] : face.stretches) {
      plan.lines.push_back({face.segment->id, face.origin + t0 * face.direction, face.origin + t1 * face.direction});
    }
  }
  plan.chains = chainLines(plan.lines);
  return plan;
}

std::string floorPlanDxf(const FloorPlan& plan) {
  DxfDocument dxf({{"PLAN_WALLS", 7}, {"PLAN_OPENINGS", 3}});
  const Eigen::Vector3d up = Eigen::Vector3d::UnitZ();
  for (const PlanChain& chain : plan.chains) dxf.addPolyline("PLAN_WALLS", chain.vertices, up, chain.closed);
  for (const PlanOpening& opening : plan.openings) {
    const std::array<Eigen::Vector3d, 2> ends{opening.start, opening.end};
    dxf.addPolyline("PLAN_OPENINGS", ends, up, false);
  }
  return dxf.text();
}

std::string floorPlanSvg(const FloorPlan& plan) {
  // Survey coordinates are too large for SVG's single-precision renderers at millimetre scale:
  // the drawing is relative to its lower-left corner, which the caption gives.
  Eigen::Vector2d low(std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity());
  Eigen::Vector2d high = -low;
  const auto extend = [&](const Eigen::Vector3d& p) {
    low = low.cwiseMin(p.head<2>());
    high = high.cwiseMax(p.head<2>());
  };
  for (const PlanChain& chain : plan.chains) {
    for (const Eigen::Vector3d& p : chain.vertices) extend(p);
  }
  for (const PlanOpening& opening : plan.openings) {
    extend(opening.start);
    extend(opening.end);
  }
  if (!std::isfinite(low.x())) low = high = Eigen::Vector2d::Zero();
  constexpr double kMargin = 500.0;  // mm around the drawing
  const Eigen::Vector2d size = (high - low) * 1e3 + Eigen::Vector2d::Constant(2.0 * kMargin);
  const auto x = [&](const Eigen::Vector3d& p) { return fixed((p.x() - low.x()) * 1e3 + kMargin, 3); };
  const auto y = [&](const Eigen::Vector3d& p) { return fixed((high.y() - p.y()) * 1e3 + kMargin, 3); };
  const std::string height = fixed(plan.height_m, 3);
  std::string svg = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
  svg += "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" + fixed(size.x(), 3) + "mm\" height=\"" +
         fixed(size.y(), 3) + "mm\" viewBox=\"0 0 " + fixed(size.x(), 3) + " " + fixed(size.y(), 3) + "\">\n";
  svg += "<title>Floor plan, section at z = " + height + " m</title>\n";
  svg += "<desc>Plumb floor plan: wall faces cut at z = " + height +
         " m. Scale 1:1, one unit is one millimetre: the world point (x, y) in metres is drawn at (" +
         fixed(kMargin, 0) + " + 1000 (x - " + fixed(low.x(), 4) + "), " + fixed(kMargin, 0) + " + 1000 (" +
         fixed(high.y(), 4) + " - y)); y points north, up the page.</desc>\n";
  svg += "<g fill=\"none\" stroke=\"black\" stroke-width=\"20\" stroke-linejoin=\"miter\">\n";
  for (const PlanChain& chain : plan.chains) {
    svg += chain.closed ? "<polygon points=\"" : "<polyline points=\"";
    for (std::size_t i = 0; i < chain.vertices.size(); ++i) {
      if (i > 0) svg += ' ';
      svg += x(chain.vertices[i]) + "," + y(chain.vertices[i]);
    }
    svg += "\"/>\n";
  }
  svg += "</g>\n<g stroke=\"black\" stroke-width=\"10\" stroke-dasharray=\"60 40\">\n";
  for (const PlanOpening& opening : plan.openings) {
    svg += "<line x1=\"" + x(opening.start) + "\" y1=\"" + y(opening.start) + "\" x2=\"" + x(opening.end) + "\" y2=\"" +
           y(opening.end) + "\"/>\n";
  }
  svg += "</g>\n<text x=\"" + fixed(kMargin, 0) + "\" y=\"" + fixed(kMargin * 0.6, 0) +
         "\" font-family=\"sans-serif\" font-size=\"150\">Section at z = " + height + " m</text>\n";
  svg += "</svg>\n";
  return svg;
}

}  // namespace plumb::cad
