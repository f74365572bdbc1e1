#include "engine/view/clip_region.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "engine/core/error.h"

namespace plumb::view {
namespace {

HalfSpace halfSpace(const Eigen::Vector3d& point, const Eigen::Vector3d& normal) {
  return {normal.x(), normal.y(), normal.z(), -normal.dot(point)};
}

// The smallest and largest value of n . x + d over the corners of the box from `min` to `max`.
std::pair<double, double> range(const HalfSpace& h, const Eigen::Vector3d& min, const Eigen::Vector3d& max) {
  double low = h[3], high = h[3];
  for (Eigen::Index a = 0; a < 3; ++a) {
    const double n = h[a];
    low += n * (n >= 0.0 ? min[a] : max[a]);
    high += n * (n >= 0.0 ? max[a] : min[a]);
  }
  return {low, high};
}

}  // namespace

Eigen::Vector3d ClipRegion::anchor() const {
  if (box) return box->centre;
  if (!planes.empty()) return planes.front().point;
  return Eigen::Vector3d::Zero();
}

ClipHalfSpaces ClipRegion::halfSpaces() const {
  ClipHalfSpaces spaces;
  if (box) {
    const Eigen::Matrix3d axes = Eigen::AngleAxisd(box->yaw_rad, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    for (Eigen::Index a = 0; a < 3; ++a) {
      const Eigen::Vector3d axis = axes.col(a);
      spaces.box_faces.push_back(halfSpace(box->centre + box->half_size[a] * axis, -axis));
      spaces.box_faces.push_back(halfSpace(box->centre - box->half_size[a] * axis, axis));
    }
  }
  spaces.keep_outside_box = keep_outside_box;
  for (const ClipPlane& plane : planes) spaces.planes.push_back(halfSpace(plane.point, plane.normal));
  return spaces;
}

bool ClipHalfSpaces::keeps(const Eigen::Vector3d& position) const {
  auto holds = [&](const HalfSpace& h) { return h.head<3>().dot(position) + h[3] >= 0.0; };
  if (!std::all_of(planes.begin(), planes.end(), holds)) return false;
  if (box_faces.empty()) return true;
  return std::all_of(box_faces.begin(), box_faces.end(), holds) != keep_outside_box;
}

bool ClipHalfSpaces::cutsAway(const Eigen::Vector3d& min, const Eigen::Vector3d& max) const {
  for (const HalfSpace& h : planes) {
    if (range(h, min, max).second < 0.0) return true;
  }
  if (box_faces.empty()) return false;
  bool wholly_inside = true;
  for (const HalfSpace& h : box_faces) {
    const auto [low, high] = range(h, min, max);
    if (high < 0.0 && !keep_outside_box) return true;  // wholly outside one face
    if (low < 0.0) wholly_inside = false;
  }
  return keep_outside_box && wholly_inside;
}

void checkClipRegion(const ClipRegion& region, const char* what) {
  if (region.box) {
    const ClipBox& box = *region.box;
    if (!box.centre.allFinite() || !std::isfinite(box.yaw_rad) || !box.half_size.allFinite() ||
        !(box.half_size.minCoeff() > 0.0)) {
      throw Error(std::string(what) + ": the clip box needs a finite centre and turn and a size above 0 on each axis");
    }
  }
  for (std::size_t i = 0; i < region.planes.size(); ++i) {
    const ClipPlane& plane = region.planes[i];
    if (!plane.point.allFinite() || !plane.normal.allFinite() || std::abs(plane.normal.norm() - 1.0) > 1e-6) {
      throw Error(std::string(what) + ": clip plane " + std::to_string(i + 1) +
                  " needs a finite point and a unit normal");
    }
  }
  const std::size_t planes = region.planes.size() + (region.box ? 6 : 0);
  if (planes > ClipRegion::kMaxPlanes) {
    throw Error(std::string(what) + ": " + std::to_string(planes) + " clip planes (the box's six included); at most " +
                std::to_string(ClipRegion::kMaxPlanes));
  }
}

ClipRegion ClipSettings::region() const {
  ClipRegion region = slice ? horizontalSlice(slice_bottom_z, slice_thickness) : ClipRegion{};
  if (slab) {
    const ClipRegion about = slabAbout(slab->point, slab->normal, slab->thickness);
    region.planes.insert(region.planes.end(), about.planes.begin(), about.planes.end());
  }
  region.box = box;
  region.keep_outside_box = keep_outside_box;
  region.planes.insert(region.planes.end(), planes.begin(), planes.end());
  return region;
}

ClipRegion horizontalSlice(double bottom_z, double thickness) {
  ClipRegion region;
  region.planes.push_back({{0.0, 0.0, bottom_z}, Eigen::Vector3d::UnitZ()});
  region.planes.push_back({{0.0, 0.0, bottom_z + thickness}, -Eigen::Vector3d::UnitZ()});
  return region;
}

ClipRegion slabAbout(const Eigen::Vector3d& point, const Eigen::Vector3d& normal, double thickness) {
  const Eigen::Vector3d n = normal.normalized();
  ClipRegion region;
  region.planes.push_back({point - 0.5 * thickness * n, n});
  region.planes.push_back({point + 0.5 * thickness * n, -n});
  return region;
}

}  // namespace plumb::view
