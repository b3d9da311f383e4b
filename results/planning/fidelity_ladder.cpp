#include "planning/fidelity_ladder.hpp"

#include "simulation/static_equilibrium.hpp"
#include "solver/hybrid_basis.hpp"

namespace railvsi {
namespace {

// Cheapest first; the last rung that applies to a scene is its reference.
// The modal and hybrid interaction rungs run the condensed direct method on
// the structure's modes, or on the track in FE and the bridge's modes.
const std::vector<LadderRung> kLadder = {
    {LoadModel::kMovingForces, StructureBackend::kModal, "none"},
    {LoadModel::kMovingForces, StructureBackend::kFiniteElements, "none"},
    {LoadModel::kInteraction, StructureBackend::kModal, "linear-hertz"},
    {LoadModel::kInteraction, StructureBackend::kModal, "hertz"},
    {LoadModel::kInteraction, StructureBackend::kHybrid, "linear-hertz"},
    {LoadModel::kInteraction, StructureBackend::kHybrid, "hertz"},
    {LoadModel::kInteraction, StructureBackend::kFiniteElements, "rigid"},
    {LoadModel::kInteraction, StructureBackend::kFiniteElements, "linear-hertz"},
    {LoadModel::kInteraction, StructureBackend::kFiniteElements, "hertz"},
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

ScenePlan ladder_plan(const LadderRung& rung, double modal_cutoff_hz) {
  ScenePlan plan;
  plan.rung.model = rung.model_name();
  plan.rung.structure = rung.structure_name();
  plan.rung.contact_law = rung.contact_law;
  // Not "planner": run_at_rung keeps the law and unilaterality rung_scene()
  // put in the analysis.
  plan.chosen_by = "price";
  plan.reasons = {"a rung of the accuracy price"};
  if (rung.structure != StructureBackend::kFiniteElements) plan.modal_cutoff_hz = modal_cutoff_hz;
  plan.impact_repeats_on_fe = false;
  return plan;
}

}  // namespace railvsi
