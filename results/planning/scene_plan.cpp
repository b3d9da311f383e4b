#include "planning/scene_plan.hpp"

#include <algorithm>

#include "solver/hybrid_basis.hpp"
#include "solver/lanczos_slices.hpp"
#include "solver/modal_basis.hpp"
#include "envelopes/code_filter.hpp"

namespace railvsi {

StudyAsks scene_asks(const Scene& scene) {
  StudyAsks a;
  if (!scene.fidelity.asks) {
    a.wheel_unloading = a.comfort = !scene.train.is_moving_forces();
    return a;
  }
  return asks_from_list(*scene.fidelity.asks);
}

StudyAsks asks_from_list(const std::vector<std::string>& list) {
  const auto has = [&](const char* what) { return std::find(list.begin(), list.end(), what) != list.end(); };
  StudyAsks a;
  a.deck = has("deck");
  a.wheel_unloading = has("wheel_unloading");
  a.comfort = has("comfort");
  a.section_forces = has("section_forces");
  return a;
}

PlannerInput planner_input(const Scene& scene, const StudyAsks& asks, const DeckFrequencies& f, int modes_below_cutoff) {
  PlannerInput in;
  in.asks = asks;
  in.irregularity = scene.irregularity != nullptr;
  in.load_model = scene.train.is_moving_forces();
  in.f0_hz = f.f0_hz;
  in.f3_hz = f.f3_hz;
  in.modes_below_cutoff = modes_below_cutoff;
  in.tolerance = scene.fidelity.tolerance;
  if (!in.load_model) {
    // How the hybrid structure would split it: a scan of the matrices.
    const HybridPartition h = hybrid_partition(*scene.structure);
    if (h.unavailable.empty()) {
      in.track_dofs = h.track_dofs;
      in.interface_dofs = h.interface_dofs;
      in.interior_dofs = h.interior_dofs;
    }
  }
  return in;
}

int count_modes(const std::shared_ptr<const StructureModel>& structure, double cutoff_hz,
                const std::vector<double>& lowest_hz, int max_dofs) {
  if (!(cutoff_hz > 0.0)) return -1;
  const auto below_cutoff = [&](const std::vector<double>& frequencies_hz) {
    return static_cast<int>(
        std::count_if(frequencies_hz.begin(), frequencies_hz.end(), [&](double f) { return f <= cutoff_hz; }));
  };
  const int known = below_cutoff(lowest_hz);
  if (known < static_cast<int>(lowest_hz.size()) || known > kMaxModalModes) return known;
  if (structure->num_dofs() > max_dofs) return -1;
  const Eigen::Index counted = count_modes_below(structure->K(), structure->M(), cutoff_hz);
  return counted < 0 ? -1 : static_cast<int>(counted);
}

namespace {

Rung rung_of_analysis(const Scene& scene) {
  Rung r;
  r.structure = "fe";
  // Moving forces on the modal backend of the analysis are stepped by HHT,
  // not by the exact recurrence of the "moving_forces/modal" rung: the rung
  // stays "fe" and run.fidelity.structure_backend names the modes.
  if (scene.train.is_moving_forces()) return r;
  if (scene.analysis.structure_backend == StructureBackend::kModal) r.structure = "modal";
  if (scene.analysis.structure_backend == StructureBackend::kHybrid) r.structure = "hybrid";
  r.model = "interaction";
  r.contact_law = scene.analysis.contact.law;
  r.unilateral = scene.analysis.contact.unilateral.value_or(scene.analysis.contact.law != "rigid");
  return r;
}

}  // namespace

ScenePlan plan_scene(const Scene& scene, const DeckFrequencies& f) {
  const FidelityRequest& req = scene.fidelity;
  ScenePlan p;
  if (req.mode == FidelityRequest::Mode::kAuto) {
    const double cutoff = kModalCutoffMargin * code_cutoff_hz(f.f0_hz, f.f3_hz);
    // Counted only where the planner may choose a modal rung: moving forces
    // (interaction stays on FE, kModalInteractionNotTrusted).
    const bool modal_possible = scene.train.is_moving_forces();
    const int modes =
        modal_possible && f.f0_hz > 0.0 && f.f3_hz > 0.0 ? count_modes(scene.structure, cutoff, f.lowest_hz) : -1;
    const EffectsPlan e = plan_effects(planner_input(scene, scene_asks(scene), f, modes));
    p.rung = e.rung;
    p.chosen_by = "planner";
    p.modal_cutoff_hz = e.modal_cutoff_hz;
    p.escalate_below_fraction = e.escalate_below_fraction;
    p.escalation_dt_factor = e.escalation_dt_factor;
    p.reasons = e.reasons;
    p.modes_below_cutoff = modes;
    return p;
  }
  p.rung = rung_of_analysis(scene);
  if (req.mode == FidelityRequest::Mode::kAsGiven) {
    p.chosen_by = "analysis";
    p.reasons.push_back("no fidelity given: the FE structure with the analysis options as given");
    return p;
  }
  p.rung.model = req.model;
  p.rung.structure = req.structure;
  p.chosen_by = req.reasons.empty() ? "pinned" : "planner";
  p.reasons = req.reasons.empty() ? std::vector<std::string>{"pinned in the scene"} : req.reasons;
  p.escalate_below_fraction = req.escalate_below_fraction;
  p.escalation_dt_factor = req.escalation_dt_factor;
  if (p.rung.structure == "modal")
    p.modal_cutoff_hz = req.modal_cutoff_hz.value_or(kModalCutoffMargin * code_cutoff_hz(f.f0_hz, f.f3_hz));
  if (p.rung.structure == "hybrid")
    p.modal_cutoff_hz = req.modal_cutoff_hz.value_or(kHybridCutoffFactor * code_cutoff_hz(f.f0_hz, f.f3_hz));
  return p;
}

void apply_rung_structure(const ScenePlan& plan, AnalysisOptions& analysis) {
  if (plan.rung.model != "interaction") return;
  const StructureBackend backend = plan.rung.structure == "modal"    ? StructureBackend::kModal
                                   : plan.rung.structure == "hybrid" ? StructureBackend::kHybrid
                                                                     : StructureBackend::kFiniteElements;
  if (backend == StructureBackend::kFiniteElements) return;
  if (analysis.structure_backend == backend && analysis.modal_modes > 0) return;
  analysis.structure_backend = backend;
  if (plan.modal_cutoff_hz > 0.0) analysis.modal_cutoff_hz = plan.modal_cutoff_hz;
}

nlohmann::json pinned_fidelity_json(const EffectsPlan& plan) {
  nlohmann::json j = {{"model", plan.rung.model}, {"structure", plan.rung.structure}};
  if (plan.rung.model == "interaction") {
    j["contact_law"] = plan.rung.contact_law;
    if (plan.rung.contact_law == "linear-hertz") j["unilateral"] = plan.rung.unilateral;
  }
  if (plan.rung.structure == "modal" || plan.rung.structure == "hybrid") j["modal_cutoff_hz"] = plan.modal_cutoff_hz;
  if (plan.escalate_below_fraction) j["escalate_below_fraction"] = *plan.escalate_below_fraction;
  if (plan.escalation_dt_factor) j["escalation_dt_factor"] = *plan.escalation_dt_factor;
  j["reasons"] = plan.reasons;
  return j;
}

}  // namespace railvsi
