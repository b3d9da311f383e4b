#pragma once
// The rungs `vsi price` climbs: one line of a table per rung (model,
// structure, contact law, modes, and the function that runs it), from the
// cheapest and least complete to the most complete. A new rung (e.g. the
// modal interaction rung) is one more line of kLadder in fidelity_ladder.cpp.
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "solver/modal_basis.hpp"
#include "simulation/load_model.hpp"
#include "simulation/result.hpp"
#include "simulation/scene.hpp"
#include "solver/structure_backend.hpp"
#include "solver/structure_operator.hpp"

namespace railvsi {

// What a rung needs beyond its scene, shared by every run of one price
// (immutable, safe across threads).
struct RungResources {
  // The FE structure operator of the scene's dt (cached per dt by the caller).
  std::function<std::shared_ptr<const StructureOperator>()> structure_operator;
  // The structure's modes up to the modal cut-off, computed once.
  std::function<std::shared_ptr<const ModalBasis>()> modal_basis;
};

struct LadderRung {
  LoadModel model;
  StructureBackend structure;  // full FE (HHT on K_bar), the structure's modes, or hybrid (track FE, bridge modes)
  std::string contact_law;  // "none" for moving forces, else a contact law name
  // Runs the rung's scene (rung_scene()). Throws InputError when the rung
  // cannot run this scene (e.g. rigid contact with alpha > -0.02).
  Result (*run)(const Scene& scene, const RungResources& resources);

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

}  // namespace railvsi
