// The simulated scenes. Each is built in a local frame: metres, z up, the floor at z = 0.
// Furniture keeps a gap to the walls so that every recorded corner is a corner of the planes
// named with it (a box touching a wall would add hidden faces coplanar with the wall).

#include "reco/sim/scenes.h"

#include "engine/core/error.h"
#include "reco/sim/scene_builder.h"

namespace plumb::reco::sim {
namespace {

struct Palette {
  MaterialId wall, floor, ceiling, wood, metal, fabric, door, glass, stone, asphalt;
};

Palette standardPalette(SceneBuilder& b) {
  return {b.material("plaster", {232, 228, 218}, 0.80),   b.material("oak floor", {156, 112, 72}, 0.45),
          b.material("ceiling", {246, 246, 244}, 0.85),   b.material("walnut", {110, 74, 48}, 0.40),
          b.material("steel", {188, 192, 198}, 0.60),     b.material("fabric", {70, 92, 140}, 0.30),
          b.material("door", {172, 134, 92}, 0.50),       b.material("glass", {88, 118, 138}, 0.08),
          b.material("sandstone", {206, 188, 150}, 0.65), b.material("asphalt", {72, 72, 76}, 0.20)};
}

}  // namespace

const std::vector<std::string>& sceneNames() {
  static const std::vector<std::string> names{"room", "office", "stairs", "facade", "hall"};
  return names;
}

Scene makeScene(std::string_view name) {
  if (name == "room") return roomScene();
  if (name == "office") return officeScene();
  if (name == "stairs") return stairsScene();
  if (name == "facade") return facadeScene();
  if (name == "hall") return hallScene();
  throw Error("unknown scene '" + std::string(name) + "': choose room, office, stairs, facade or hall");
}

// A 7 x 5 x 2.5 m room: a window recess in the y+ wall, a recessed door in the x- wall, a sofa,
// a desk with a monitor and a tall cabinet that throws a long scan shadow. The room's eight
// corners are the first eight truth corners.
Scene roomScene() {
  SceneBuilder b("room");
  const Palette p = standardPalette(b);
  const BoxFaces room = b.interior({{0, 0, 0}, {7, 5, 2.5}}, "room", p.wall, p.floor, p.ceiling);

  b.opening({.front = room.y_max,
             .back = b.plane(kY, 5.25, -1, "window glass"),
             .back_is_recess = true,
             .along = kX,
             .from = 2.5,
             .to = 4.3,
             .bottom = 0.9,
             .top = 2.1,
             .floor = std::nullopt,
             .reveal = p.wall,
             .recess = p.glass,
             .name = "window"});
  b.opening({.front = room.x_min,
             .back = b.plane(kX, -0.12, +1, "door leaf"),
             .back_is_recess = true,
             .along = kY,
             .from = 0.6,
             .to = 1.5,
             .bottom = 0.0,
             .top = 2.05,
             .floor = room.z_min,
             .reveal = p.wall,
             .recess = p.door,
             .name = "door"});

  b.solidBox({{2.2, 0.3, 0.0}, {4.0, 1.2, 0.45}}, "sofa", p.fabric, room.z_min);
  const BoxFaces desk = b.solidBox({{4.6, 0.6, 0.0}, {6.2, 1.4, 0.75}}, "desk", p.wood, room.z_min);
  b.solidBox({{5.2, 1.1, 0.75}, {5.8, 1.16, 1.12}}, "monitor", p.metal, desk.z_max);
  b.solidBox({{0.5, 3.9, 0.0}, {1.7, 4.45, 2.0}}, "cabinet", p.metal, room.z_min);

  b.station({3.3, 2.6, 1.45});
  b.station({5.6, 3.9, 1.45});
  return std::move(b).build();
}

// A 16 m corridor with three offices along it (walls 0.15 m thick), a door from the corridor
// into each office, a door between the first two offices, two windows per office and a desk in
// each. One station in the corridor and one per office.
Scene officeScene() {
  SceneBuilder b("office");
  const Palette p = standardPalette(b);
  const BoxFaces corridor = b.interior({{0, 0, 0}, {16, 2, 2.6}}, "corridor", p.wall, p.floor, p.ceiling);
  const std::array<double, 3> room_min_x{0.0, 5.35, 10.8};
  const std::array<double, 3> room_max_x{5.2, 10.65, 16.0};
  std::array<BoxFaces, 3> rooms{};
  for (std::size_t i = 0; i < rooms.size(); ++i) {
    const std::string name = "office " + std::to_string(i + 1);
    rooms[i] = b.interior({{room_min_x[i], 2.15, 0}, {room_max_x[i], 7, 2.6}}, name, p.wall, p.floor, p.ceiling);
    const double door_x = room_min_x[i] + 1.0;
    b.opening({.front = corridor.y_max,
               .back = rooms[i].y_min,
               .back_is_recess = false,
               .along = kX,
               .from = door_x,
               .to = door_x + 0.9,
               .bottom = 0.0,
               .top = 2.1,
               .floor = corridor.z_min,
               .reveal = p.wall,
               .recess = p.wall,
               .name = name + " door"});
    for (int w = 0; w < 2; ++w) {
      const double window_x = room_min_x[i] + 0.9 + 2.1 * w;
      b.opening({.front = rooms[i].y_max,
                 .back = b.plane(kY, 7.3, -1, "window glass"),
                 .back_is_recess = true,
                 .along = kX,
                 .from = window_x,
                 .to = window_x + 1.4,
                 .bottom = 0.9,
                 .top = 2.2,
                 .floor = std::nullopt,
                 .reveal = p.wall,
                 .recess = p.glass,
                 .name = name + " window " + std::to_string(w + 1)});
    }
    const BoxFaces desk = b.solidBox({{room_min_x[i] + 2.6, 5.6, 0}, {room_min_x[i] + 4.2, 6.4, 0.75}}, name + " desk",
                                     p.wood, corridor.z_min);
    b.solidBox({{room_min_x[i] + 3.1, 6.2, 0.75}, {room_min_x[i] + 3.7, 6.25, 1.1}}, name + " monitor", p.metal,
               desk.z_max);
    b.station({(room_min_x[i] + room_max_x[i]) / 2, 4.3, 1.5});
  }
  b.opening({.front = rooms[0].x_max,
             .back = rooms[1].x_min,
             .back_is_recess = false,
             .along = kY,
             .from = 5.4,
             .to = 6.3,
             .bottom = 0.0,
             .top = 2.1,
             .floor = corridor.z_min,
             .reveal = p.wall,
             .recess = p.wall,
             .name = "office 1-2 door"});
  b.solidBox({{8.6, 2.5, 0}, {9.8, 2.95, 1.9}}, "office 2 cabinet", p.metal, corridor.z_min);
  // The corridor station first: it sees into every office through the doors.
  Scene scene = std::move(b).build();
  scene.stations.insert(scene.stations.begin(), Eigen::Vector3d(8.0, 1.0, 1.5));
  scene.default_station_count = scene.stations.size();
  return scene;
}

// A straight staircase of 16 steps (rise 0.1875 m, going 0.28 m, 1.2 m wide, against the y-
// wall) from the ground floor (z = 0) to an upper floor slab (top at z = 3, 0.25 m thick) in a
// 9 x 3 m stairwell 5.6 m high. Stations on the ground floor and on the upper floor.
Scene stairsScene() {
  SceneBuilder b("stairs");
  const Palette p = standardPalette(b);
  const BoxFaces well = b.interior({{0, 0, 0}, {9, 3, 5.6}}, "stairwell", p.wall, p.floor, p.ceiling);

  constexpr int kSteps = 16;
  constexpr double kStart = 2.0, kGoing = 0.28, kRise = 0.1875, kWidth = 1.2;
  constexpr double kEnd = kStart + kSteps * kGoing;
  constexpr double kUpper = kSteps * kRise, kSlab = 0.25;

  const PlaneId upper = b.plane(kZ, kUpper, +1, "upper floor");
  const PlaneId side = b.plane(kY, kWidth, +1, "stair side");
  const PlaneId wall = well.y_min;
  PlaneId previous_tread = well.z_min;
  for (int i = 0; i < kSteps; ++i) {
    const std::string name = "step " + std::to_string(i + 1);
    const double x0 = kStart + i * kGoing, x1 = x0 + kGoing;
    const double z0 = i * kRise, z1 = z0 + kRise;
    const PlaneId riser = b.plane(kX, x0, -1, name + " riser");
    const PlaneId tread = b.plane(kZ, z1, +1, name + " tread");
    b.quad(riser, {{{0, 0}, {0, kWidth}, {z0, z1}}}, p.stone);
    b.quad(tread, {{{x0, x1}, {0, kWidth}, {0, 0}}}, p.stone);
    b.quad(side, {{{x0, x1}, {0, 0}, {0, z1}}}, p.stone);
    for (PlaneId flank : {side, wall}) {
      b.corner(riser, previous_tread, flank);  // inner corner at the foot of the riser
      b.corner(riser, tread, flank);           // nosing
    }
    b.edge(riser, previous_tread, 0, kWidth);
    b.edge(riser, tread, 0, kWidth);
    b.edge(side, riser, z0, z1);
    b.edge(side, tread, x0, x1);
    previous_tread = tread;
  }
  // The upper floor continues the last tread; its front edge overhangs the open space beside
  // the stair, and the stair mass ends in a vertical back face below the slab.
  const PlaneId soffit = b.plane(kZ, kUpper - kSlab, -1, "upper floor soffit");
  const PlaneId slab_edge = b.plane(kX, kEnd, -1, "upper floor edge");
  const PlaneId stair_back = b.plane(kX, kEnd, +1, "stair back");
  b.quad(upper, {{{kEnd, 9}, {0, 3}, {0, 0}}}, p.floor);
  b.quad(soffit, {{{kEnd, 9}, {0, 3}, {0, 0}}}, p.ceiling);
  b.quad(slab_edge, {{{0, 0}, {kWidth, 3}, {kUpper - kSlab, kUpper}}}, p.wall);
  b.quad(stair_back, {{{0, 0}, {0, kWidth}, {0, kUpper - kSlab}}}, p.stone);
  b.corner(slab_edge, upper, well.y_max);
  b.corner(slab_edge, soffit, well.y_max);
  b.edge(slab_edge, upper, kWidth, 3);
  b.edge(slab_edge, soffit, kWidth, 3);
  b.edge(stair_back, side, 0, kUpper - kSlab);
  b.edge(stair_back, well.z_min, 0, kWidth);

  b.station({1.0, 2.2, 1.5});
  b.station({7.8, 2.0, 4.5});
  Scene scene = std::move(b).build();
  scene.default_station_count = 2;
  return scene;
}

// A 24 m wide, 12 m high building front on a street: four recessed shop windows and a recessed
// door on the ground floor, two upper floors of six windows, a balcony slab on the first floor
// and a cornice. Stations stand on the street 9 m in front of the facade.
Scene facadeScene() {
  SceneBuilder b("facade");
  const Palette p = standardPalette(b);
  const PlaneId street = b.plane(kZ, 0, +1, "street");
  const PlaneId front = b.plane(kY, 0, -1, "facade");
  b.quad(street, {{{-12, 36}, {-16, 0}, {0, 0}}}, p.asphalt);
  b.quad(front, {{{0, 24}, {0, 0}, {0, 12}}}, p.stone);
  b.edge(front, street, 0, 24);

  auto window = [&](double x0, double x1, double z0, double z1, double depth, const std::string& name) {
    b.opening({.front = front,
               .back = b.plane(kY, depth, -1, name + " glass"),
               .back_is_recess = true,
               .along = kX,
               .from = x0,
               .to = x1,
               .bottom = z0,
               .top = z1,
               .floor = std::nullopt,
               .reveal = p.stone,
               .recess = p.glass,
               .name = name});
  };
  const std::array<double, 4> shop_x{1.5, 5.5, 14.0, 18.5};
  for (std::size_t i = 0; i < shop_x.size(); ++i) {
    window(shop_x[i], shop_x[i] + 3.5, 0.6, 2.8, 0.20, "shop window " + std::to_string(i + 1));
  }
  b.opening({.front = front,
             .back = b.plane(kY, 0.35, -1, "entrance door"),
             .back_is_recess = true,
             .along = kX,
             .from = 10.3,
             .to = 12.3,
             .bottom = 0.0,
             .top = 2.6,
             .floor = street,
             .reveal = p.stone,
             .recess = p.door,
             .name = "entrance"});
  for (int floor = 1; floor <= 2; ++floor) {
    const double z0 = 0.9 + 3.6 * floor;
    for (int i = 0; i < 6; ++i) {
      const double x0 = 1.3 + 3.8 * i;
      window(x0, x0 + 1.4, z0, z0 + 1.6, 0.25, "floor " + std::to_string(floor) + " window " + std::to_string(i + 1));
    }
  }
  b.solidBox({{8.4, -1.3, 3.45}, {14.2, 0, 3.65}}, "balcony", p.stone, front);
  b.solidBox({{0, -0.45, 11.55}, {24, 0, 12.0}}, "cornice", p.stone, front);

  for (double x : {12.0, 3.0, 21.0}) b.station({x, -9.0, 1.6});
  Scene scene = std::move(b).build();
  scene.default_station_count = 3;
  return scene;
}

// A bare 6 x 8 x 3 m hall with one station in the middle: the speed benchmark's scene, whose
// y = 0 wall is a plain 6 x 3 m wall 4 m from the scanner.
Scene hallScene() {
  SceneBuilder b("hall");
  const Palette p = standardPalette(b);
  b.interior({{0, 0, 0}, {6, 8, 3}}, "hall", p.wall, p.floor, p.ceiling);
  b.station({3.0, 4.0, 1.5});
  return std::move(b).build();
}

}  // namespace plumb::reco::sim
