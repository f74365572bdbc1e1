#pragma once
// The catalogue of simulated scenes: room, office, stairs, facade, hall. docs/simulator.md describes
// each with its dimensions and stations.

#include <string>
#include <string_view>
#include <vector>

#include "reco/sim/scene.h"

namespace plumb::reco::sim {

// The names makeScene() accepts, in a stable order.
const std::vector<std::string>& sceneNames();

// Builds a scene in its local frame. Throws plumb::Error for an unknown name.
Scene makeScene(std::string_view name);

Scene roomScene();
Scene officeScene();
Scene stairsScene();
Scene facadeScene();
Scene hallScene();

}  // namespace plumb::reco::sim
