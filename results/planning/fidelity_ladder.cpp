#include "planning/fidelity_ladder.hpp"

#include "analysis/modal_moving_forces.hpp"
#include "simulation/simulation.hpp"
#include "simulation/static_equilibrium.hpp"
#include "solver/hybrid_basis.hpp"

namespace railvsi {
namespace {

Result run_fe(const Scene& scene, const RungResources& resources) {
  const Simulation simulation(scene, resources.structure_operator());
  return simulation.run();
}

Result run_modal_moving_forces_rung(const Scene& scene, const RungResources& resources) {
  return run_modal_moving_forces(scene, *resources.modal_basis());
}

// Cheapest first; the last rung that applies to a scene is its reference.
// The modal and hybrid interaction rungs (the condensed direct method on
// the structure's modes, or on the track in FE and the bridge's modes) run
// on the operator of resources.structure_operator too: the caller builds
// the modal or hybrid one for them.
const std::vector<LadderRung> kLadder = {
    {LoadModel::kMovingForces, StructureBackend::kModal, "none", run_modal_moving_forces_rung},
    {LoadModel::kMovingForces, StructureBackend::kFiniteElements, "none", run_fe},
    {LoadModel::kInteraction, StructureBackend::kModal, "linear-hertz", run_fe},
    {LoadModel::kInteraction, StructureBackend::kModal, "hertz", run_fe},
    {LoadModel::kInteraction, StructureBackend::kHybrid, "linear-hertz", run_fe},
    {LoadModel::kInteraction, StructureBackend::kHybrid, "hertz", run_fe},
    {LoadModel::kInteraction, StructureBackend::kFiniteElements, "rigid", run_fe},
    {LoadModel::kInteraction, StructureBackend::kFiniteElements, "linear-hertz", run_fe},
    {LoadModel::kInteraction, StructureBackend::kFiniteElements, "hertz", run_fe},
};

}  // namespace

std::string LadderRung::label() const { return model_name() + " / " + structure_name() + " / " + contact_law; }

const std::vector<LadderRung>& fidelity_ladder() { return kLadder; }

bool rung_applies(const LadderRung& rung, const Scene& scene) {
  if (rung.model == LoadModel::kMovingForces) return true;
  if (scene.train.is_moving_forces()) return false;
  if (rung.structure == StructureBackend::kFiniteElements) return true;
  const bool track = hybrid_partition(*scene.structure).unavailable.empty();
  return rung.structure == StructureBackend::kHybrid ? track : !track;
}

Scene rung_scene(const LadderRung& rung, const Scene& scene, double dt_s) {
  Scene s = scene;
  s.analysis.dt_s = dt_s;
  if (rung.model == LoadModel::kMovingForces) {
    if (!s.train.is_moving_forces()) {
      s.train.moving_forces = axle_loads(s.train);
      s.train.vehicles.clear();
    }
    return s;
  }
  s.analysis.structure_backend = rung.structure == StructureBackend::kModal    ? StructureBackend::kModal
                                 : rung.structure == StructureBackend::kHybrid ? StructureBackend::kHybrid
                                                                            : StructureBackend::kFiniteElements;
  s.analysis.contact.law = rung.contact_law;
  s.analysis.contact.unilateral =
      rung.contact_law == "linear-hertz" ? std::optional<bool>(true) : std::optional<bool>();
  return s;
}

}  // namespace railvsi
