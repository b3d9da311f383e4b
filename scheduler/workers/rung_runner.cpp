#include "workers/rung_runner.hpp"

#include "analysis/modal_moving_forces.hpp"
#include "core/input_error.hpp"
#include "simulation/simulation.hpp"

namespace railvsi::scheduler {

void record_rung(const Scene& scene, const ScenePlan& plan, const Rung& rung, RunSummary& summary) {
  FidelityRecord& f = summary.fidelity;
  f.rung = rung.name();
  f.chosen_by = plan.chosen_by;
  f.reasons = plan.reasons;
  f.dt_s = summary.dt_s;
  f.ignores = rung_ignores(rung, scene.irregularity != nullptr, f.modal_cutoff_hz, plan.escalate_below_fraction);
}

Result run_at_rung(const Scene& scene, const ScenePlan& plan, const RungModels& models) {
  if (plan.rung.exact_modal()) {
    const std::shared_ptr<const ModalBasis> basis = models.modal_basis(plan.modal_cutoff_hz);
    Result r = run_modal_moving_forces(scene, *basis);
    record_rung(scene, plan, plan.rung, r.summary);
    return r;
  }
  // The rung's contact law (the planner's for "auto"; a pinned one is
  // already in the analysis options).
  Scene on_rung = scene;
  if (plan.rung.model == "interaction" && plan.chosen_by == "planner") {
    on_rung.analysis.contact.law = plan.rung.contact_law;
    on_rung.analysis.contact.unilateral = plan.rung.unilateral;
  }
  apply_rung_structure(plan, on_rung.analysis);
  const std::shared_ptr<const StructureOperator> op = models.fe_operator(on_rung);
  Result r = Simulation(on_rung, op).run();
  record_rung(on_rung, plan, plan.rung, r.summary);
  if (!plan.escalate_below_fraction || !r.status.ok() || scene.train.is_moving_forces()) return r;
  const auto why = escalation_reason(r.summary, *plan.escalate_below_fraction, plan.escalation_dt_factor);
  if (!why) return r;
  // The contact law changes neither K_bar nor the rail flexibility: the same
  // operator, unless the time step changes too (wheel quantities asked).
  Scene full = on_rung;
  full.analysis.contact.law = "hertz";
  full.analysis.contact.unilateral = true;
  const double dt_factor = plan.escalation_dt_factor.value_or(1.0);
  if (dt_factor != 1.0) full.analysis.dt_s *= dt_factor;
  Result again = Simulation(full, dt_factor != 1.0 ? models.fe_operator(full) : op).run();
  record_rung(full, plan, escalated(plan.rung), again.summary);
  again.summary.fidelity.escalation = *why;
  again.summary.wall_s += r.summary.wall_s;
  return again;
}

}  // namespace railvsi::scheduler
