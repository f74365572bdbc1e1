#include "reco/sim/truth_json.h"

#include <nlohmann/json.hpp>

namespace plumb::reco::sim {
namespace {

nlohmann::json array3(const Eigen::Vector3d& v) {
  return nlohmann::json::array({v.x(), v.y(), v.z()});
}

}  // namespace

std::string truthJson(const Scene& scene, const SceneFrame& frame, const ScannerSettings& settings,
                      const SimulationReport& report) {
  using nlohmann::json;
  json root;
  root["format"] = "plumb-simulation-truth";
  root["version"] = 1;
  root["scene"] = scene.name;
  root["seed"] = settings.seed;
  root["rotation_deg"] = frame.rotation_deg;
  root["offset"] = array3(frame.offset);
  root["noise"] = {{"sigma_m", settings.noise_m},
                   {"range_ppm", settings.range_noise_ppm},
                   {"angular_urad", settings.angular_noise_urad}};
  const ScanPattern& pattern = report.pattern;
  root["scanner"] = {{"columns", pattern.columns},
                     {"rows", pattern.rows},
                     {"azimuth_step_deg", pattern.azimuthStepDeg()},
                     {"elevation_step_deg", pattern.elevationStepDeg()},
                     {"min_elevation_deg", pattern.min_elevation_deg},
                     {"max_elevation_deg", pattern.max_elevation_deg},
                     {"max_range_m", settings.max_range_m},
                     {"dropout", settings.dropout}};
  json stations = json::array();
  for (const Eigen::Vector3d& station : report.stations) stations.push_back(array3(station));
  root["stations"] = std::move(stations);
  root["points"] = {{"written", report.counts.returns},
                    {"rays", report.counts.rays},
                    {"misses", report.counts.misses},
                    {"dropped", report.counts.dropped}};

  json planes = json::array();
  for (const TruthPlane& local : scene.planes) {
    const TruthPlane plane = frame.toWorld(local);
    planes.push_back({{"id", plane.id}, {"name", plane.name}, {"normal", array3(plane.normal)}, {"d", plane.offset}});
  }
  root["planes"] = std::move(planes);
  json corners = json::array();
  for (std::size_t i = 0; i < scene.corners.size(); ++i) {
    const TruthCorner& corner = scene.corners[i];
    corners.push_back({{"id", i}, {"position", array3(frame.toWorld(corner.position))}, {"planes", corner.planes}});
  }
  root["corners"] = std::move(corners);
  json edges = json::array();
  for (std::size_t i = 0; i < scene.edges.size(); ++i) {
    const TruthEdge& edge = scene.edges[i];
    edges.push_back({{"id", i},
                     {"start", array3(frame.toWorld(edge.start))},
                     {"end", array3(frame.toWorld(edge.end))},
                     {"planes", edge.planes}});
  }
  root["edges"] = std::move(edges);
  return root.dump(1) + "\n";
}

}  // namespace plumb::reco::sim
