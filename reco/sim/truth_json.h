#pragma once
// The ground-truth file of a simulated scan (format described in docs/simulator.md).

#include <string>

#include "reco/sim/simulation.h"

namespace plumb::reco::sim {

// The JSON text of the truth of `scene` scanned as `report` says, in world coordinates
// (rotated by settings.rotation_deg, then offset).
std::string truthJson(const Scene& scene, const SceneFrame& frame, const ScannerSettings& settings,
                      const SimulationReport& report);

}  // namespace plumb::reco::sim
