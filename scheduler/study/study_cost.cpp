#include "study/study_cost.hpp"

#include <algorithm>
#include <map>
#include <set>

#include <fmt/format.h>

#include "io/json_document.hpp"
#include "io/scene_loader.hpp"
#include "planning/cost_model.hpp"
#include "planning/scene_plan.hpp"
#include "simulation/simulation.hpp"
#include "study/structure_key.hpp"

namespace railvsi::scheduler {

namespace {

// Inputs computed for another job of the same operator, at this job's steps.
CostInputs with_steps(CostInputs in, const Scene& scene) {
  in.steps = static_cast<double>(planned_steps(scene));
  return in;
}

}  // namespace

StudyCostEstimate estimate_study_cost(const StudyPlan& plan) {
  StudyCostEstimate e;
  std::map<std::string, Scene> by_train;  // the first job's scene of each train
  std::map<std::string, int> modes_of_train;  // on the exact modal rung
  std::set<std::string> operators, structures;
  std::map<std::string, CostInputs> hybrid_inputs;  // by operator key
  ImportedStructures imports;  // a model's files read once for every train
  for (const JobSpec& job : plan.jobs) {
    auto it = by_train.find(job.train);
    if (it == by_train.end()) {
      // File names in a job are absolute (made so at submission).
      const std::string name = "job " + job.id.substr(0, 12);
      it = by_train.emplace(job.train, parse_scene(parse_json_text(job.scene, name), "/", name, &imports)).first;
    }
    Scene scene = it->second;
    scene.speed_mps = job.speed_kmh / 3.6;
    scene.analysis.dt_s = job.dt_s;
    // Jobs on the exact modal rung cost their modes, not the FE operator;
    // on the hybrid rung, the track's FE and the bridge's modes.
    const bool modal = job.rung == "moving_forces/modal" && scene.fidelity.modal_cutoff_hz;
    const bool hybrid = job.rung == "interaction/hybrid";
    int modes = job.modes;
    if (modal && modes == 0) {
      // Not expanded here: counted, up to the size where Lanczos is cheap.
      auto [m, fresh] = modes_of_train.try_emplace(job.train, 0);
      if (fresh) m->second = std::max(1, count_modes(scene.structure, *scene.fidelity.modal_cutoff_hz, {}, 20000));
      modes = m->second;
    }
    if (hybrid) modes = job.hybrid_modes;
    const StructureBackend backend =
        modal ? StructureBackend::kModal : hybrid ? StructureBackend::kHybrid : StructureBackend::kFiniteElements;
    const auto inputs = hybrid_inputs.find(job.operator_key);
    // The hybrid partition scans the structure: once per operator.
    const CostInputs in = inputs != hybrid_inputs.end() ? with_steps(inputs->second, scene)
                                                        : cost_inputs(scene, backend, modes);
    if (hybrid) hybrid_inputs.emplace(job.operator_key, in);
    const CostPrediction p = predict_cost(in);
    e.cpu_s += p.loop_cpu_s;
    if (operators.insert(job.operator_key).second) {
      // The hybrid structure's reduction once per structure, whatever the dt.
      const double setup_s =
          p.setup_cpu_s - (structures.insert(structure_part(job.operator_key)).second ? 0.0 : p.structure_setup_cpu_s);
      e.cpu_s += setup_s;
      e.setup_cpu_s += setup_s;
    }
    ++e.jobs;
  }
  e.setups = operators.size();
  return e;
}

std::string describe(const StudyCostEstimate& e) {
  return fmt::format("estimated CPU time {:.3g} s for {} jobs ({:.3g} s of it for {} setups: factorizations or "
                     "modal bases; cost model: "
                     "docs/accuracy-and-price.md)",
                     e.cpu_s, e.jobs, e.setup_cpu_s, e.setups);
}

}  // namespace railvsi::scheduler
