// plumb grow: the planes around a point, as a click in the viewer would find them.

#include <unistd.h>

#include <CLI/App.hpp>
#include <CLI/Config.hpp>
#include <CLI/Formatter.hpp>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>

#include "engine/core/atomic_file.h"
#include "engine/core/error.h"
#include "engine/lod/node_cache.h"
#include "engine/lod/octree.h"
#include "engine/lod/octree_builder.h"
#include "reco/region_grower.h"
#include "ui/cli/arguments.h"
#include "ui/cli/command.h"
#include "ui/cli/progress_line.h"

namespace plumb::cli {
namespace {

struct GrowOptions {
  std::string cloud;
  std::string seed;
  double view_distance = 3.0;
  std::string detail;
  double plane_threshold = 0.02;
  std::string json;
};

bool isOctree(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  char magic[8] = {};
  in.read(magic, sizeof magic);
  return in.gcount() == 8 && std::string_view(magic, 8) == "PLUMBOCT";
}

// A point file becomes a temporary octree, removed when the command ends.
struct TemporaryOctree {
  std::string path;
  ~TemporaryOctree() {
    if (!path.empty()) std::filesystem::remove(path);
  }
};

nlohmann::json vector3(const Eigen::Vector3d& v) {
  return {v.x(), v.y(), v.z()};
}

}  // namespace

Command addGrowCommand(CLI::App& plumb) {
  auto options = std::make_shared<GrowOptions>();
  CLI::App* sub = plumb.add_subcommand("grow", "Grow the planes around a seed point (paper sections 3.4 to 3.7)");
  sub->footer("Example: plumb grow site.plumb --seed 512003.2,5403001.0,251.2 --view-distance 3 --json planes.json");
  sub->add_option("cloud", options->cloud, "An octree (plumb import) or a point file, imported on the fly")
      ->required()
      ->check(CLI::ExistingFile);
  sub->add_option("--seed", options->seed, "The picked point X,Y,Z (world coordinates)")->required();
  auto* distance = sub->add_option("--view-distance", options->view_distance,
                                   "Distance of the camera from the seed in metres: nearer means more detail")
                       ->check(finiteIn(0.05, 100'000))
                       ->capture_default_str();
  sub->add_option("--detail", options->detail, "Override the detail the view implies: low, medium, high or full")
      ->check(CLI::IsMember({"low", "medium", "high", "full"}))
      ->excludes(distance);
  sub->add_option("--tp", options->plane_threshold, "Plane threshold t_p in metres (the precision of the planes)")
      ->check(finiteIn(1e-5, 10))
      ->capture_default_str();
  sub->add_option("--json", options->json, "Write the result as JSON (docs/grow-json.md)");

  auto run = [options]() -> int {
    const Eigen::Vector3d seed = parseVector3(options->seed, "--seed");
    TemporaryOctree temporary;
    std::string octree_path = options->cloud;
    if (!isOctree(octree_path)) {
      temporary.path =
          (std::filesystem::temp_directory_path() / ("plumb-grow-" + std::to_string(::getpid()) + ".plumb")).string();
      lod::BuildOptions build;
      build.sources = lod::fileSources({options->cloud});
      build.output = temporary.path;
      ProgressLine progress("grow: importing");
      build.progress = [&](std::string_view phase, std::uint64_t done, std::uint64_t total) {
        progress.update(phase, done, total);
      };
      const lod::BuildReport report = lod::buildOctree(build);
      progress.finish();
      std::printf("imported %s points from %s\n", withThousands(report.points).c_str(), options->cloud.c_str());
      octree_path = temporary.path;
    }
    const auto octree = lod::Octree::open(octree_path);
    lod::NodeCache cache(octree, std::size_t{1} << 30);

    reco::ParameterConstants constants;
    constants.plane_threshold_m = options->plane_threshold;
    reco::GrowParameters parameters =
        reco::parametersForView(reco::viewFromDistance(seed, options->view_distance), constants);
    if (!options->detail.empty()) {
      const double density = options->detail == "low"      ? constants.min_density
                             : options->detail == "medium" ? std::sqrt(constants.min_density * constants.max_density)
                             : options->detail == "high"   ? constants.max_density
                                                           : std::pow(octree->spacing(octree->header().depth), -3.0);
      parameters = reco::parametersForDensity(seed, density, parameters.seed_radius_m, constants);
    }

    double first_progress_ms = -1.0;
    const reco::GrowSnapshot result = reco::growRegions(cache, parameters, {}, [&](const reco::GrowSnapshot& s) {
      if (first_progress_ms < 0.0) first_progress_ms = s.elapsed_ms;
    });

    std::printf("grew %zu segment%s around %.3f %.3f %.3f at level %u (spacing %.4f m)\n", result.segments.size(),
                result.segments.size() == 1 ? "" : "s", seed.x(), seed.y(), seed.z(), result.level,
                octree->spacing(result.level));
    std::printf("  parameters  r_s %.3f m, d %.0f points/m^3, r %.4f m, t_p %.4f m\n", parameters.seed_radius_m,
                parameters.density, parameters.search_radius_m, parameters.plane_threshold_m);
    for (std::size_t s = 0; s < result.segments.size(); ++s) {
      const reco::SegmentSnapshot& segment = result.segments[s];
      const reco::Plane& plane = segment.plane;
      std::printf("  segment %zu  %s points, normal %+.4f %+.4f %+.4f, rms %.2f mm, lambda2 %.3g m^2\n", s,
                  withThousands(segment.points).c_str(), plane.normal.x(), plane.normal.y(), plane.normal.z(),
                  plane.rms * 1e3, plane.lambda2);
    }
    for (const reco::Edge& edge : result.edges) {
      std::printf("  edge        segments %u-%u, %.3f m from %.3f %.3f %.3f to %.3f %.3f %.3f\n", edge.segments[0],
                  edge.segments[1], (edge.end - edge.start).norm(), edge.start.x(), edge.start.y(), edge.start.z(),
                  edge.end.x(), edge.end.y(), edge.end.z());
    }
    for (const reco::Corner& corner : result.corners) {
      std::printf("  corner      segments %u-%u-%u at %.4f %.4f %.4f\n", corner.segments[0], corner.segments[1],
                  corner.segments[2], corner.position.x(), corner.position.y(), corner.position.z());
    }
    std::printf("  time        first snapshot %.1f ms, %s %.1f ms; %s cell visits, %s point tests\n", first_progress_ms,
                result.converged ? "converged" : "stopped", result.elapsed_ms,
                withThousands(result.cells_visited).c_str(), withThousands(result.points_tested).c_str());

    if (!options->json.empty()) {
      nlohmann::json segments = nlohmann::json::array();
      for (const reco::SegmentSnapshot& segment : result.segments) {
        const reco::Plane& plane = segment.plane;
        segments.push_back(
            {{"plane",
              {{"normal", vector3(plane.normal)},
               {"d", plane.offset},
               {"origin", vector3(plane.centroid)},
               {"tangent", vector3(plane.tangent)},
               {"bitangent", vector3(plane.bitangent)}}},
             {"statistics", {{"points", segment.points}, {"lambda2", plane.lambda2}, {"rms_m", plane.rms}}}});
      }
      nlohmann::json edges = nlohmann::json::array();
      for (const reco::Edge& edge : result.edges) {
        edges.push_back({{"start", vector3(edge.start)},
                         {"end", vector3(edge.end)},
                         {"segments", edge.segments},
                         {"support_points", edge.support_points}});
      }
      nlohmann::json corners = nlohmann::json::array();
      for (const reco::Corner& corner : result.corners) {
        corners.push_back(
            {{"position", vector3(corner.position)}, {"segments", corner.segments}, {"support", corner.support}});
      }
      const nlohmann::json root{{"format", "plumb-grow"},
                                {"version", 1},
                                {"cloud", options->cloud},
                                {"seed", vector3(seed)},
                                {"parameters",
                                 {{"seed_radius_m", parameters.seed_radius_m},
                                  {"density", parameters.density},
                                  {"spacing_m", parameters.spacing_m},
                                  {"search_radius_m", parameters.search_radius_m},
                                  {"plane_threshold_m", parameters.plane_threshold_m},
                                  {"level", result.level}}},
                                {"segments", segments},
                                {"edges", edges},
                                {"corners", corners},
                                {"timing",
                                 {{"first_progress_ms", first_progress_ms},
                                  {"converged_ms", result.elapsed_ms},
                                  {"cells_visited", result.cells_visited},
                                  {"points_tested", result.points_tested}}}};
      const std::string text = root.dump(1) + "\n";
      AtomicFile file(options->json);
      file.write(text.data(), text.size());
      file.commit();
    }
    return 0;
  };
  return {sub, run};
}

}  // namespace plumb::cli
