#pragma once
// Walls grown on a simulated scan, for the floor plan tests: the scene simulated, imported, and a
// grow at a click on each wall, as a user makes them in the viewer.

#include <Eigen/Core>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "cad/floor_plan.h"
#include "cad/project.h"
#include "engine/core/error.h"
#include "engine/lod/node_cache.h"
#include "engine/lod/octree_builder.h"
#include "reco/region_grower.h"
#include "reco/sim/simulation.h"
#include "tests/support/temp_directory.h"

namespace plumb::cad::test {

inline const Eigen::Vector3d kOffset(512000.0, 5403000.0, 250.0);

// A wall of a simulated scene: a click on it (scene frame) and its true plane, x or y = value.
struct TrueWall {
  Eigen::Vector3d click;
  int axis;  // 0: x = value, 1: y = value
  double value;
};

// `scene` simulated at 2 mm noise with `points`, imported, and a grow at each wall's click seen
// from 3 m: a project of the clicked segments, each once (a click on a surface a segment already
// holds adds nothing, as in the viewer), and for each segment the wall first clicked on it.
struct GrownWalls {
  Project project;
  std::vector<TrueWall> walls;  // walls[id - 1]: the true wall of segment id
};
inline GrownWalls grownWalls(const char* scene, std::uint64_t points, const std::vector<TrueWall>& walls) {
  const plumb::test::TempDirectory directory(std::string("plumb_FloorPlanOfGrownWalls_") + scene);
  reco::sim::SimulationRequest request;
  request.scene = scene;
  request.scanner.noise_m = 0.002;
  request.scanner.seed = 1;
  request.target_points = points;
  request.offset = kOffset;
  request.points_path = directory.file("scan.ply");
  reco::sim::simulate(request);
  lod::BuildOptions build;
  build.sources = lod::fileSources({request.points_path});
  build.output = directory.file("scan.plumb");
  lod::buildOctree(build);
  lod::NodeCache cache(lod::Octree::open(build.output), 256 << 20);
  GrownWalls grown;
  Project& project = grown.project;
  for (const TrueWall& wall : walls) {
    const Eigen::Vector3d seed = kOffset + wall.click;
    const reco::GrowSnapshot result = reco::growRegions(cache, reco::parametersForView(reco::viewFromDistance(seed, 3.0)));
    const reco::SegmentSnapshot* clicked = nullptr;
    for (const reco::SegmentSnapshot& segment : result.segments) {
      if (segment.plane.valid && segment.outline &&
          (clicked == nullptr || segment.plane.distance(seed) < clicked->plane.distance(seed))) {
        clicked = &segment;
      }
    }
    if (clicked == nullptr) throw Error("no segment grew at a click");
    bool held = false;
    for (const Segment& earlier : project.segments) {
      held = held || (std::abs(earlier.plane.normal.dot(clicked->plane.normal)) > std::cos(0.1 * M_PI / 180.0) &&
                      earlier.plane.distance(clicked->plane.centroid) < 0.005 &&
                      std::abs(static_cast<double>(earlier.plane.point_count) -
                               static_cast<double>(clicked->plane.point_count)) <
                          0.01 * static_cast<double>(earlier.plane.point_count));
    }
    if (held) continue;
    const ItemId id = project.segments.size() + 1;
    project.segments.push_back({id, "Wall " + std::to_string(id), kNoItem, clicked->plane, *clicked->outline});
    grown.walls.push_back(wall);
  }
  return grown;
}

// How far `p` lies from the true plane of `wall`.
inline double offWall(const TrueWall& wall, const Eigen::Vector3d& p) {
  return std::abs((p - kOffset)[wall.axis] - wall.value);
}

// Every line of the plan on its wall's true plane, within `tolerance`.
inline void expectLinesOnTheirWalls(const FloorPlan& plan, const std::vector<TrueWall>& walls, double tolerance) {
  for (const PlanLine& line : plan.lines) {
    const TrueWall& wall = walls.at(line.segment - 1);
    const Eigen::Vector3d a = line.start - kOffset, b = line.end - kOffset;
    std::printf("wall %llu: (%.3f, %.3f) to (%.3f, %.3f), ends %.3f and %.3f mm off its true plane\n",
                static_cast<unsigned long long>(line.segment), a.x(), a.y(), b.x(), b.y(), offWall(wall, line.start) * 1e3,
                offWall(wall, line.end) * 1e3);
    EXPECT_LT(offWall(wall, line.start), tolerance) << "wall " << line.segment;
    EXPECT_LT(offWall(wall, line.end), tolerance) << "wall " << line.segment;
  }
}

}  // namespace plumb::cad::test
