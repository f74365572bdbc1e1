#include "reco/sim/scene_builder.h"

#include <algorithm>
#include <cassert>
#include <cmath>

namespace plumb::reco::sim {
namespace {

int uAxis(int axis) {
  return (axis + 1) % 3;
}
int vAxis(int axis) {
  return (axis + 2) % 3;
}

Rect2 toRect(int axis, const std::array<std::array<double, 2>, 3>& ranges) {
  const auto& u = ranges[static_cast<std::size_t>(uAxis(axis))];
  const auto& v = ranges[static_cast<std::size_t>(vAxis(axis))];
  assert(u[0] < u[1] && v[0] < v[1] && "empty or inverted rectangle");
  return {u[0], u[1], v[0], v[1]};
}

bool overlaps(const Rect2& a, const Rect2& b) {
  return a.u0 < b.u1 && b.u0 < a.u1 && a.v0 < b.v1 && b.v0 < a.v1;
}

}  // namespace

MaterialId SceneBuilder::material(std::string name, std::array<std::uint8_t, 3> rgb, double reflectivity) {
  scene_.materials.push_back({std::move(name), rgb, reflectivity});
  return static_cast<MaterialId>(scene_.materials.size() - 1);
}

PlaneId SceneBuilder::plane(int axis, double coord, int facing, const std::string& name) {
  assert(axis >= 0 && axis < 3 && (facing == 1 || facing == -1));
  for (std::size_t i = 0; i < keys_.size(); ++i) {
    if (keys_[i].axis == axis && keys_[i].facing == facing && std::abs(keys_[i].coord - coord) < 1e-9) {
      return static_cast<PlaneId>(i);
    }
  }
  const auto id = static_cast<PlaneId>(keys_.size());
  keys_.push_back({axis, coord, facing});
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();
  normal[axis] = facing;
  scene_.planes.push_back({id, name, normal, -facing * coord});
  return id;
}

void SceneBuilder::quad(PlaneId plane, const Rect2& extent, MaterialId material) {
  const PlaneKey& k = key(plane);
  scene_.quads.push_back({k.axis, k.coord, extent, 0, 0, plane, material});
  pending_holes_.emplace_back();
}

void SceneBuilder::quad(PlaneId plane, const std::array<std::array<double, 2>, 3>& ranges, MaterialId material) {
  quad(plane, toRect(key(plane).axis, ranges), material);
}

void SceneBuilder::cutHole(PlaneId plane, const std::array<std::array<double, 2>, 3>& ranges) {
  const Rect2 hole = toRect(key(plane).axis, ranges);
  bool cut = false;
  for (std::size_t i = 0; i < scene_.quads.size(); ++i) {
    if (scene_.quads[i].plane == plane && overlaps(scene_.quads[i].extent, hole)) {
      pending_holes_[i].push_back(hole);
      cut = true;
    }
  }
  assert(cut && "cutHole: no rectangle of that plane overlaps the hole");
  (void)cut;
}

void SceneBuilder::corner(PlaneId a, PlaneId b, PlaneId c) {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  int axes_seen = 0;
  for (PlaneId id : {a, b, c}) {
    position[key(id).axis] = key(id).coord;
    axes_seen |= 1 << key(id).axis;
  }
  assert(axes_seen == 7 && "a corner needs planes of three different axes");
  (void)axes_seen;
  scene_.corners.push_back({position, {a, b, c}});
}

void SceneBuilder::edge(PlaneId a, PlaneId b, double from, double to) {
  assert(key(a).axis != key(b).axis && "an edge needs planes of two different axes");
  const int free_axis = 3 - key(a).axis - key(b).axis;
  Eigen::Vector3d start = Eigen::Vector3d::Zero();
  start[key(a).axis] = key(a).coord;
  start[key(b).axis] = key(b).coord;
  Eigen::Vector3d end = start;
  start[free_axis] = from;
  end[free_axis] = to;
  scene_.edges.push_back({start, end, {a, b}});
}

BoxFaces SceneBuilder::interior(const Box& box, const std::string& name, MaterialId walls, MaterialId floor,
                                MaterialId ceiling) {
  const Eigen::Vector3d& lo = box.min;
  const Eigen::Vector3d& hi = box.max;
  // Inward normals: each face looks into the room.
  const BoxFaces f{plane(kX, lo.x(), +1, name + " wall x-"), plane(kX, hi.x(), -1, name + " wall x+"),
                   plane(kY, lo.y(), +1, name + " wall y-"), plane(kY, hi.y(), -1, name + " wall y+"),
                   plane(kZ, lo.z(), +1, name + " floor"),   plane(kZ, hi.z(), -1, name + " ceiling")};
  const std::array<double, 2> x{lo.x(), hi.x()}, y{lo.y(), hi.y()}, z{lo.z(), hi.z()};
  quad(f.x_min, {x, y, z}, walls);
  quad(f.x_max, {x, y, z}, walls);
  quad(f.y_min, {x, y, z}, walls);
  quad(f.y_max, {x, y, z}, walls);
  quad(f.z_min, {x, y, z}, floor);
  quad(f.z_max, {x, y, z}, ceiling);
  for (PlaneId fz : {f.z_min, f.z_max}) {
    for (PlaneId fy : {f.y_min, f.y_max}) {
      for (PlaneId fx : {f.x_min, f.x_max}) corner(fx, fy, fz);
    }
  }
  for (PlaneId fx : {f.x_min, f.x_max}) {
    for (PlaneId fy : {f.y_min, f.y_max}) edge(fx, fy, lo.z(), hi.z());
  }
  for (PlaneId fz : {f.z_min, f.z_max}) {
    for (PlaneId fy : {f.y_min, f.y_max}) edge(fy, fz, lo.x(), hi.x());
    for (PlaneId fx : {f.x_min, f.x_max}) edge(fx, fz, lo.y(), hi.y());
  }
  return f;
}

BoxFaces SceneBuilder::solidBox(const Box& box, const std::string& name, MaterialId material,
                                std::optional<PlaneId> resting_on) {
  const Eigen::Vector3d& lo = box.min;
  const Eigen::Vector3d& hi = box.max;
  // The face that lies on `resting_on` is hidden; the support plane stands in for it.
  auto face = [&](int axis, double coord, int facing, const char* side) {
    if (resting_on && key(*resting_on).axis == axis && std::abs(key(*resting_on).coord - coord) < 1e-9) {
      return std::pair{*resting_on, false};
    }
    return std::pair{plane(axis, coord, facing, name + " " + side), true};
  };
  const std::array sides{face(kX, lo.x(), -1, "x-"), face(kX, hi.x(), +1, "x+"),     face(kY, lo.y(), -1, "y-"),
                         face(kY, hi.y(), +1, "y+"), face(kZ, lo.z(), -1, "bottom"), face(kZ, hi.z(), +1, "top")};
  const std::array<double, 2> x{lo.x(), hi.x()}, y{lo.y(), hi.y()}, z{lo.z(), hi.z()};
  for (const auto& [id, visible] : sides) {
    if (visible) quad(id, {x, y, z}, material);
  }
  const BoxFaces f{sides[0].first, sides[1].first, sides[2].first, sides[3].first, sides[4].first, sides[5].first};
  for (PlaneId fz : {f.z_min, f.z_max}) {
    for (PlaneId fy : {f.y_min, f.y_max}) {
      for (PlaneId fx : {f.x_min, f.x_max}) corner(fx, fy, fz);
    }
  }
  for (PlaneId fx : {f.x_min, f.x_max}) {
    for (PlaneId fy : {f.y_min, f.y_max}) edge(fx, fy, lo.z(), hi.z());
  }
  for (PlaneId fz : {f.z_min, f.z_max}) {
    for (PlaneId fy : {f.y_min, f.y_max}) edge(fy, fz, lo.x(), hi.x());
    for (PlaneId fx : {f.x_min, f.x_max}) edge(fx, fz, lo.y(), hi.y());
  }
  return f;
}

void SceneBuilder::opening(const Opening& o) {
  const int wall_axis = key(o.front).axis;
  assert(key(o.back).axis == wall_axis && o.along != wall_axis && o.along != kZ);
  const double front = key(o.front).coord;
  const double back = key(o.back).coord;
  const std::array<double, 2> across{std::min(front, back), std::max(front, back)};
  const std::array<double, 2> along{o.from, o.to};
  const std::array<double, 2> up{o.bottom, o.top};

  // World-axis ranges from per-axis values: the wall axis, the horizontal axis and z.
  auto ranges = [&](const std::array<double, 2>& on_wall_axis, const std::array<double, 2>& on_along,
                    const std::array<double, 2>& on_z) {
    std::array<std::array<double, 2>, 3> r{};
    r[static_cast<std::size_t>(wall_axis)] = on_wall_axis;
    r[static_cast<std::size_t>(o.along)] = on_along;
    r[kZ] = on_z;
    return r;
  };

  cutHole(o.front, ranges({front, front}, along, up));
  if (o.back_is_recess) {
    quad(o.back, ranges({back, back}, along, up), o.recess);
  } else {
    cutHole(o.back, ranges({back, back}, along, up));
  }

  // Reveal faces look into the opening.
  const PlaneId side_lo = plane(o.along, o.from, +1, o.name + " reveal " + (o.along == kX ? "x-" : "y-"));
  const PlaneId side_hi = plane(o.along, o.to, -1, o.name + " reveal " + (o.along == kX ? "x+" : "y+"));
  const PlaneId head = plane(kZ, o.top, -1, o.name + " head");
  const PlaneId sill = o.floor ? *o.floor : plane(kZ, o.bottom, +1, o.name + " sill");
  std::array<std::array<double, 2>, 3> side_ranges{};
  side_ranges[static_cast<std::size_t>(wall_axis)] = across;
  side_ranges[kZ] = up;
  quad(side_lo, side_ranges, o.reveal);
  quad(side_hi, side_ranges, o.reveal);
  quad(head, ranges(across, along, {o.top, o.top}), o.reveal);
  quad(sill, ranges(across, along, {o.bottom, o.bottom}), o.reveal);

  for (PlaneId face : {o.front, o.back}) {
    for (PlaneId side : {side_lo, side_hi}) {
      corner(face, side, head);
      corner(face, side, sill);
      edge(face, side, o.bottom, o.top);
    }
    edge(face, head, o.from, o.to);
    // A door has no edge across its threshold: the floor runs through, and the wall's own
    // edge with the floor stops at the jambs. A door leaf at the bottom of a recess does meet
    // the floor.
    const bool recess_bottom = face == o.back && o.back_is_recess;
    if (o.floor && !recess_bottom) {
      removeEdgeSpan(face, *o.floor, o.from, o.to);
    } else {
      edge(face, sill, o.from, o.to);
    }
  }
  for (PlaneId side : {side_lo, side_hi}) {
    edge(side, head, across[0], across[1]);
    edge(side, sill, across[0], across[1]);
  }
}

void SceneBuilder::removeEdgeSpan(PlaneId a, PlaneId b, double from, double to) {
  const int free_axis = 3 - key(a).axis - key(b).axis;
  std::vector<TruthEdge> kept;
  for (const TruthEdge& e : scene_.edges) {
    const bool same_planes = (e.planes[0] == a && e.planes[1] == b) || (e.planes[0] == b && e.planes[1] == a);
    const double lo = std::min(e.start[free_axis], e.end[free_axis]);
    const double hi = std::max(e.start[free_axis], e.end[free_axis]);
    if (!same_planes || hi <= from || lo >= to) {
      kept.push_back(e);
      continue;
    }
    TruthEdge piece = e;
    if (lo < from) {
      piece.start[free_axis] = lo;
      piece.end[free_axis] = from;
      kept.push_back(piece);
    }
    if (hi > to) {
      piece.start[free_axis] = to;
      piece.end[free_axis] = hi;
      kept.push_back(piece);
    }
  }
  scene_.edges = std::move(kept);
}

Scene SceneBuilder::build() && {
  for (std::size_t i = 0; i < scene_.quads.size(); ++i) {
    scene_.quads[i].first_hole = static_cast<std::uint32_t>(scene_.holes.size());
    scene_.quads[i].hole_count = static_cast<std::uint32_t>(pending_holes_[i].size());
    scene_.holes.insert(scene_.holes.end(), pending_holes_[i].begin(), pending_holes_[i].end());
  }
  return std::move(scene_);
}

}  // namespace plumb::reco::sim
