#pragma once
// The rungs `vsi price` climbs: one line of a table per rung (model,
// structure, contact law), from the cheapest and least complete to the most
// complete. Each runs through the rung runner (run_at_rung) on the plan
// ladder_plan() makes of it, as a worker runs a job. A new rung (e.g. the
// modal interaction rung) is one more line of kLadder in fidelity_ladder.cpp.
#include <string>
#include <vector>

#include "simulation/load_model.hpp"
#include "simulation/scene.hpp"
#include "solver/structure_backend.hpp"
#include "planning/scene_plan.hpp"

namespace railvsi {

struct LadderRung {
  LoadModel model;
  StructureBackend structure;  // full FE (HHT on K_bar), the structure's modes, or hybrid (track FE, bridge modes)
  std::string contact_law;  // "none" for moving forces, else a contact law name

  std::string model_name() const { return load_model_name(model); }
  std::string structure_name() const { return structure_backend_name(structure); }
  // "moving_forces / fe / none"
  std::string label() const;
};

// Every rung, cheapest first; the last applicable one is the reference.
const std::vector<LadderRung>& fidelity_ladder();

// Whether a rung can describe the scene's train: moving-force rungs always
// (a multibody train becomes its static wheel loads), interaction rungs only
// for a multibody train; interaction on the modes only on a structure
// without track (on a track it misses the tolerance at any cut-off), on
// the hybrid structure only on one with track.
bool rung_applies(const LadderRung& rung, const Scene& scene);

// The scene as the rung runs it, at time step dt_s: a multibody train as
// moving forces for a moving-force rung (axle_loads: what "as":
// "moving_forces" gives in a scene document), the rung's contact law
// (linear Hertz unilateral, hertz and rigid with their own default; G, wheels
// per contact and rail lines kept from the scene).
Scene rung_scene(const LadderRung& rung, const Scene& scene, double dt_s);

// The plan run_at_rung runs a rung_scene() on: the rung as pinned (its law
// is the scene's), modal_cutoff_hz for the modes it keeps, no escalation
// and no repeat on FE after a wheel impact: the price measures each rung as
// it is.
ScenePlan ladder_plan(const LadderRung& rung, double modal_cutoff_hz);

}  // namespace railvsi
