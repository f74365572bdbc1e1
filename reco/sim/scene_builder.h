#pragma once
// Builds simulator scenes from planes, rectangles, holes and the truth that goes with them.
//
// Low level: plane(), quad(), cutHole(), corner(), edge(). High level: interior() (a room seen
// from inside), solidBox() (furniture, slabs), opening() (doors, windows, recesses). The high
// level helpers record the true corners and edges of what they add, so a scene's truth is
// complete by construction.

#include <optional>
#include <string>
#include <vector>

#include "reco/sim/scene.h"

namespace plumb::reco::sim {

enum Axis : int { kX = 0, kY = 1, kZ = 2 };

struct Box {
  Eigen::Vector3d min;
  Eigen::Vector3d max;
};

// The six faces of a box by the side they lie on.
struct BoxFaces {
  PlaneId x_min, x_max, y_min, y_max, z_min, z_max;
};

class SceneBuilder {
 public:
  explicit SceneBuilder(std::string name) { scene_.name = std::move(name); }

  MaterialId material(std::string name, std::array<std::uint8_t, 3> rgb, double reflectivity);

  // The plane x[axis] = coord whose normal is facing * e_axis (facing is +1 or -1). Asking twice
  // for the same plane returns the same id (the first name stays).
  PlaneId plane(int axis, double coord, int facing, const std::string& name);

  // A rectangle on `plane`; `extent` is in the plane's (u, v) coordinates, see Rect2.
  void quad(PlaneId plane, const Rect2& extent, MaterialId material);
  // A rectangle on `plane` given as world-axis ranges: `ranges[a]` for the two axes a other than
  // the plane's own (the entry of the plane's axis is ignored).
  void quad(PlaneId plane, const std::array<std::array<double, 2>, 3>& ranges, MaterialId material);

  // Removes `hole` (world-axis ranges as above) from every rectangle of `plane`.
  void cutHole(PlaneId plane, const std::array<std::array<double, 2>, 3>& ranges);

  // A true corner of three planes of three different axes.
  void corner(PlaneId a, PlaneId b, PlaneId c);
  // A true edge where planes a and b (different axes) meet, from `from` to `to` along the third axis.
  void edge(PlaneId a, PlaneId b, double from, double to);

  void station(const Eigen::Vector3d& position) { scene_.stations.push_back(position); }

  // A room seen from inside: floor, ceiling and four walls facing inwards, with its 8 corners
  // and 12 edges. Names are "<name> floor", "<name> wall x-" and so on.
  BoxFaces interior(const Box& box, const std::string& name, MaterialId walls, MaterialId floor, MaterialId ceiling);

  // A solid box seen from outside. When `resting_on` is given the bottom face is left out and
  // the bottom corners and edges are taken with that plane (furniture on a floor).
  BoxFaces solidBox(const Box& box, const std::string& name, MaterialId material,
                    std::optional<PlaneId> resting_on = std::nullopt);

  // An opening through a wall or into it.
  struct Opening {
    PlaneId front;                 // the wall face the opening is cut into
    PlaneId back;                  // the opposite wall face (cut too) or the bottom of a recess
    bool back_is_recess = false;   // true: `back` is a new surface filling the opening at depth
    int along;                     // the horizontal axis of the wall (kX or kY)
    double from, to;               // extent along `along`
    double bottom, top;            // extent along z
    std::optional<PlaneId> floor;  // a door: the floor runs through instead of a sill
    MaterialId reveal;             // material of the reveal faces
    MaterialId recess;             // material of the recess bottom (glass, door leaf)
    std::string name;
  };
  void opening(const Opening& opening);

  Scene build() &&;

 private:
  struct PlaneKey {
    int axis;
    double coord;
    int facing;
  };
  const PlaneKey& key(PlaneId id) const { return keys_[id]; }
  // Cuts [from, to] (along the free axis) out of the recorded edges of planes a and b.
  void removeEdgeSpan(PlaneId a, PlaneId b, double from, double to);

  Scene scene_;
  std::vector<PlaneKey> keys_;
  std::vector<std::vector<Rect2>> pending_holes_;  // per quad, merged into the scene at build()
};

}  // namespace plumb::reco::sim
