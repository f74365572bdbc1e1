#include "ui/cli/grow_output.h"

#include <nlohmann/json.hpp>

#include "engine/core/atomic_file.h"
#include "engine/io/gltf_writer.h"

namespace plumb::cli {
namespace {

nlohmann::json vector3(const Eigen::Vector3d& v) {
  return {v.x(), v.y(), v.z()};
}

// A segment's regression polygon in world coordinates: its rings, and its triangulation.
nlohmann::json polygonJson(const reco::PlaneOutline& outline) {
  nlohmann::json rings = nlohmann::json::array();
  for (const auto& ring : outline.shape.rings) {
    nlohmann::json vertices = nlohmann::json::array();
    for (const Eigen::Vector2d& v : ring) vertices.push_back(vector3(outline.toWorld(v)));
    rings.push_back(std::move(vertices));
  }
  nlohmann::json vertices = nlohmann::json::array();
  for (const Eigen::Vector2d& v : outline.shape.vertices) vertices.push_back(vector3(outline.toWorld(v)));
  return {{"rings", std::move(rings)},
          {"vertices", std::move(vertices)},
          {"triangles", outline.shape.triangles},
          {"cell_m", outline.shape.cell_m}};
}

}  // namespace

void writeGrowJson(const GrowReport& report, const std::string& path) {
  const reco::GrowSnapshot& result = report.result;
  const reco::GrowParameters& parameters = report.parameters;
  nlohmann::json segments = nlohmann::json::array();
  for (const reco::SegmentSnapshot& segment : result.segments) {
    const reco::Plane& plane = segment.plane;
    nlohmann::json entry{{"plane",
                          {{"normal", vector3(plane.normal)},
                           {"d", plane.offset},
                           {"origin", vector3(plane.centroid)},
                           {"tangent", vector3(plane.tangent)},
                           {"bitangent", vector3(plane.bitangent)}}},
                         {"statistics",
                          {{"points", segment.points},
                           {"area_m2", segment.outline ? segment.outline->shape.area_m2 : 0.0},
                           {"lambda2", plane.lambda2},
                           {"rms_m", plane.rms}}}};
    if (segment.outline) entry["polygon"] = polygonJson(*segment.outline);
    segments.push_back(std::move(entry));
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
                            {"cloud", report.cloud},
                            {"seed", vector3(report.seed)},
                            {"parameters",
                             {{"seed_radius_m", parameters.seed_radius_m},
                              {"pixel_m", parameters.pixel_size_m},
                              {"click_spacing_m", parameters.click_spacing_m},
                              {"density", parameters.density},
                              {"spacing_m", parameters.spacing_m},
                              {"search_radius_m", parameters.search_radius_m},
                              {"plane_threshold_m", result.plane_threshold_m},
                              {"plane_threshold_from_data", parameters.plane_threshold_from_data},
                              {"noise_sigma_m", result.noise_sigma_m},
                              {"level", result.level},
                              {"data_spacing_m", result.data_spacing_m},
                              {"search_radius_used_m", result.search_radius_m}}},
                            {"levels",
                             {{"finest", result.finest_level},
                              {"coarsest", result.coarsest_level},
                              {"refinements", result.refinements},
                              {"coarsenings", result.coarsenings}}},
                            {"segments", segments},
                            {"edges", edges},
                            {"corners", corners},
                            {"timing",
                             {{"first_progress_ms", report.first_progress_ms},
                              {"seeded_ms", result.seeded_ms},
                              {"converged_ms", result.elapsed_ms},
                              {"cells_visited", result.cells_visited},
                              {"points_tested", result.points_tested},
                              {"tests_skipped", result.tests_skipped},
                              {"bridges", result.bridges}}}};
  const std::string text = root.dump(1) + "\n";
  AtomicFile file(path);
  file.write(text.data(), text.size());
  file.commit();
}

void writeGrowGltf(const reco::GrowSnapshot& result, const std::string& path) {
  // One colour per segment, cycling: translucent, so the cloud shows through in a viewer.
  static constexpr std::array<std::array<float, 4>, 6> kColours{{{0.90f, 0.30f, 0.25f, 0.6f},
                                                                 {0.25f, 0.60f, 0.90f, 0.6f},
                                                                 {0.35f, 0.80f, 0.35f, 0.6f},
                                                                 {0.95f, 0.75f, 0.20f, 0.6f},
                                                                 {0.70f, 0.40f, 0.85f, 0.6f},
                                                                 {0.30f, 0.80f, 0.80f, 0.6f}}};
  io::GltfScene scene;
  for (std::size_t s = 0; s < result.segments.size(); ++s) {
    const auto& outline = result.segments[s].outline;
    if (!outline) continue;
    io::GltfMesh mesh;
    mesh.name = "segment_" + std::to_string(s);
    for (const Eigen::Vector2d& v : outline->shape.vertices) mesh.positions.push_back(outline->toWorld(v));
    mesh.triangles = outline->shape.triangles;
    mesh.colour_rgba = kColours[s % kColours.size()];
    scene.meshes.push_back(std::move(mesh));
  }
  if (!result.edges.empty()) {
    io::GltfLines lines;
    lines.name = "edges";
    for (const reco::Edge& edge : result.edges) lines.segments.push_back({edge.start, edge.end});
    lines.colour_rgba = {1.0f, 1.0f, 1.0f, 1.0f};
    scene.lines.push_back(std::move(lines));
  }
  if (!result.corners.empty()) {
    io::GltfPoints points;
    points.name = "corners";
    for (const reco::Corner& corner : result.corners) points.positions.push_back(corner.position);
    points.colour_rgba = {1.0f, 0.1f, 0.1f, 1.0f};
    scene.points.push_back(std::move(points));
  }
  io::writeGlb(scene, path);
}

}  // namespace plumb::cli
