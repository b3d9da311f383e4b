#pragma once
// A scene run on its planned rung (study/scene_plan): the modal moving-force
// rung, or the FE rung (moving forces or interaction). An interaction plan
// with an escalation fraction is repeated with nonlinear unilateral Hertz
// when a contact force drops below that fraction of its static load (at the
// plan's escalation_dt_factor x dt, on an operator for that dt); the Result
// is then the repeated run's (its summary's dt_s is the one it ran at), its
// fidelity says why, and its wall time counts both runs. Every Result's fidelity names the rung, who chose
// it and why, its mode count and dt, and what it ignores and why.
#include <functional>
#include <memory>

#include "solver/hybrid_basis.hpp"
#include "solver/modal_basis.hpp"
#include "simulation/result.hpp"
#include "simulation/scene.hpp"
#include "solver/structure_operator.hpp"
#include "planning/deck_frequencies.hpp"
#include "planning/scene_plan.hpp"

namespace railvsi {

// Where the rung's structure comes from (a cache, or built for this run).
struct RungModels {
  // The operator of a scene's structure backend; `reuse`: the hybrid
  // reduction of an earlier run of the same job (another dt, or the FE
  // structure asked next), null when there is none.
  std::function<std::shared_ptr<const StructureOperator>(const Scene&, std::shared_ptr<const HybridBasis> reuse)>
      fe_operator;
  std::function<std::shared_ptr<const ModalBasis>(double cutoff_hz)> modal_basis;
};

// Throws InputError when the scene cannot run on the rung.
Result run_at_rung(const Scene& scene, const ScenePlan& plan, const RungModels& models);

// The rung's models built for one run (no cache): what `vsi simulate`,
// `vsi replay` and the report's governing cases run on.
RungModels standalone_models(const Scene& scene);

// A scene run as a worker runs it: planned by plan_scene (a stored job's
// scene carries the rung, contact law and escalation pinned at submission,
// so it needs no frequencies), then run_at_rung on standalone models. The
// one way a stored job is run again: its envelopes are the stored ones.
Result run_planned(const Scene& scene, const DeckFrequencies& frequencies = {});

// The scene as its run ran: the contact law and unilaterality the run's
// fidelity names (the planner's for "auto", Hertz after an escalation) and
// the dt it ran at. The time-step checks judge this one: judged against the
// law the scene names, "auto" understated the step 1.8x.
Scene scene_as_run(const Scene& scene, const RunSummary& summary);

// The fidelity record's rung, choice, reasons and ignores for a run of
// `scene` on `rung` (the plan's, or its escalation).
void record_rung(const Scene& scene, const ScenePlan& plan, const Rung& rung, RunSummary& summary);

}  // namespace railvsi
