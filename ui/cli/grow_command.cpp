// plumb grow: the planes around a point, as a click in the viewer would find them.

#include <CLI/App.hpp>
#include <CLI/Config.hpp>
#include <CLI/Formatter.hpp>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>

#include "engine/core/error.h"
#include "engine/lod/node_cache.h"
#include "engine/lod/octree.h"
#include "engine/view/camera_json.h"
#include "reco/data_at_click.h"
#include "reco/region_grower.h"
#include "ui/cli/arguments.h"
#include "ui/cli/clip_options.h"
#include "ui/cli/cloud_input.h"
#include "ui/cli/command.h"
#include "ui/cli/grow_output.h"
#include "ui/viewer/view_at_click.h"

namespace plumb::cli {
namespace {

struct GrowOptions {
  std::string cloud;
  std::string seed;
  double view_distance = 3.0;
  std::string camera;
  std::string detail;
  double plane_threshold = 0.02;
  std::string json;
  std::string gltf;
  ClipArguments clip;  // grows limited to a section
};

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
  auto* camera_option = sub->add_option("--camera", options->camera,
                                        "The view the click was made in: a camera JSON file (docs/camera-json.md)")
                            ->check(CLI::ExistingFile)
                            ->excludes(distance);
  sub->add_option("--detail", options->detail, "Override the detail the view implies: low, medium, high or full")
      ->check(CLI::IsMember({"low", "medium", "high", "full"}))
      ->excludes(distance)
      ->excludes(camera_option);
  CLI::Option* tp_option =
      sub->add_option("--tp", options->plane_threshold,
                      "Plane threshold t_p in metres (the precision of the planes); by default 3 times the noise "
                      "measured on the seed planes where that is more than 0.02")
          ->check(finiteIn(1e-5, 10));
  sub->add_option("--json", options->json, "Write the result as JSON (docs/grow-json.md)");
  sub->add_option("--gltf", options->gltf,
                  "Write the segments' polygons, edges and corners as a glTF 2.0 binary (.glb)");
  addClipOptions(*sub, options->clip);  // the grow takes only the points they keep

  auto run = [options, tp_option]() -> int {
    const Eigen::Vector3d seed = parseVector3(options->seed, "--seed");
    const view::ClipRegion section = clipSettingsOf(options->clip).region();
    // Read the camera before any work: a bad file is reported at once.
    reco::ViewAtClick view = reco::viewFromDistance(seed, options->view_distance);
    if (!options->camera.empty()) {
      const std::optional<reco::ViewAtClick> clicked = viewer::viewAtClick(view::readCameraJson(options->camera), seed);
      if (!clicked) throw Error(options->camera + ": the seed " + options->seed + " is behind the camera");
      view = *clicked;
    }
    const CloudInput cloud(options->cloud, "grow");
    const std::shared_ptr<const lod::Octree>& octree = cloud.octree();
    lod::NodeCache cache(octree, std::size_t{1} << 30);

    reco::ParameterConstants constants;
    constants.plane_threshold_m = options->plane_threshold;
    constants.plane_threshold_from_data = tp_option->count() == 0;
    const double full_density = std::pow(octree->spacing(octree->header().depth), -3.0);
    reco::GrowParameters parameters;
    double measure_ms = 0.0;
    if (options->detail.empty()) {
      // The data's spacing at the click, before the grow's clock starts: its time is reported.
      const auto measuring = std::chrono::steady_clock::now();
      parameters = reco::parametersForView(view, constants, reco::dataAtClick(cache, seed));
      measure_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - measuring).count();
    } else {
      const reco::Detail detail = options->detail == "low"      ? reco::Detail::kLow
                                  : options->detail == "medium" ? reco::Detail::kMedium
                                  : options->detail == "high"   ? reco::Detail::kHigh
                                                                : reco::Detail::kFull;
      const double density = reco::densityForDetail(detail, constants, full_density);
      parameters = reco::parametersForDensity(seed, density, reco::parametersForView(view).seed_radius_m, constants);
    }

    double first_progress_ms = -1.0;
    reco::GrowOptions grow_options;
    if (section.active()) {
      grow_options.keep = [spaces = section.halfSpaces()](const Eigen::Vector3d& p) { return spaces.keeps(p); };
    }
    const reco::GrowSnapshot result =
        reco::growRegions(cache, parameters, grow_options, [&](const reco::GrowSnapshot& s) {
          if (first_progress_ms < 0.0) first_progress_ms = s.elapsed_ms;
        });

    std::printf("grew %zu segment%s around %.3f %.3f %.3f at level %u (spacing %.4f m)\n", result.segments.size(),
                result.segments.size() == 1 ? "" : "s", seed.x(), seed.y(), seed.z(), result.level,
                octree->spacing(result.level));
    char threshold[96];
    if (parameters.plane_threshold_from_data) {
      std::snprintf(threshold, sizeof threshold, "t_p %.4f m (the noise measured: %.2f mm)", result.plane_threshold_m,
                    result.noise_sigma_m * 1e3);
    } else {
      std::snprintf(threshold, sizeof threshold, "t_p %.4f m", result.plane_threshold_m);
    }
    std::printf("  parameters  r_s %.3f m, d %.0f points/m^3, r %.4f m, %s\n", parameters.seed_radius_m,
                parameters.density, parameters.search_radius_m, threshold);
    if (parameters.click_spacing_m > 0.0) {
      std::printf("  view        pixel %.2f mm at the click, the points %.1f mm apart there (measured in %.1f ms)%s\n",
                  parameters.pixel_size_m * 1e3, parameters.click_spacing_m * 1e3, measure_ms,
                  parameters.density >= full_density ? ": every point" : "");
    }
    std::printf("  grown at    levels %u to %u (%s refinements, %s coarsenings), r %.4f m (data spacing %.4f m)\n",
                result.coarsest_level, result.finest_level, withThousands(result.refinements).c_str(),
                withThousands(result.coarsenings).c_str(), result.search_radius_m, result.data_spacing_m);
    for (std::size_t s = 0; s < result.segments.size(); ++s) {
      const reco::SegmentSnapshot& segment = result.segments[s];
      const reco::Plane& plane = segment.plane;
      std::printf("  segment %zu  %s points, normal %+.4f %+.4f %+.4f, rms %.2f mm, lambda2 %.3g m^2, area %.2f m^2\n",
                  s, withThousands(segment.points).c_str(), plane.normal.x(), plane.normal.y(), plane.normal.z(),
                  plane.rms * 1e3, plane.lambda2, segment.outline ? segment.outline->shape.area_m2 : 0.0);
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
    std::printf(
        "  time        first snapshot %.1f ms, the seed sphere %.1f ms, %s %.1f ms; %s cell visits, %s point tests "
        "(%s skipped), %s bridges\n",
        first_progress_ms, result.seeded_ms, result.converged ? "converged" : "stopped", result.elapsed_ms,
        withThousands(result.cells_visited).c_str(), withThousands(result.points_tested).c_str(),
        withThousands(result.tests_skipped).c_str(), withThousands(result.bridges).c_str());

    if (!options->json.empty()) {
      writeGrowJson({options->cloud, seed, parameters, result, first_progress_ms}, options->json);
    }
    if (!options->gltf.empty()) writeGrowGltf(result, options->gltf);
    return 0;
  };
  return {sub, run};
}

}  // namespace plumb::cli
