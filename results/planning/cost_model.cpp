#include "planning/cost_model.hpp"

#include <fmt/format.h>

#include "simulation/simulation.hpp"

namespace railvsi {
namespace {

// Seconds of one core, fitted by hand on `vsi price` of two scenes of
// docs/accuracy-and-price.md
// (2026-11-23, 2-core CI machine under load 14, thread CPU time): the
// ICE3 viaduct (2,296 DOFs, 1,064 rail DOFs, 32 axles, 108 modes up to
// 53 Hz) and HSLM-A1 on the 25 m beam (102 DOFs, 50 axles, 3 modes).
//  - moving forces, FE: 74 us/step on the viaduct, 4.5 us/step on the beam
//    -> 3.2e-8 s per DOF and 2.5e-8 s per axle;
//  - interaction, FE: 118-131 us/step on the viaduct (rigid, linear Hertz,
//    Hertz; 168 over the dip, more Newton iterations) -> 5.5e-8 s per DOF.
//    One interaction model size cannot separate a per-contact term: it is
//    folded into the per-DOF one, so a train with many more contacts per
//    DOF is underestimated;
//  - FE setup (factor and rail flexibility): 0.015-0.06 s on the viaduct;
// The modal rung, re-measured 2026-11-27 with tests/bench/cost_model_bench
// (thread CPU, least of 5, load 8-10 on the 2 cores) at 97f7ac8, where the
// fit above predicted 1.5-3.6x too much (measured / predicted 0.28-0.67):
//  - HSLM-A1 on the 25 m beam (102 DOFs, 3 modes, 52 loads and outputs):
//    basis 0.89 ms, run 0.76 ms at 2,663 steps to 6.4 ms at 42,602;
//  - HSLM-A1 on the ICE3 viaduct's structure as moving forces (1,208 DOFs,
//    41 modes up to 53 Hz, 53 loads and outputs): basis 71 ms, run 22 ms at
//    3,577 steps to 64 ms at 57,222.
//  The runs' slopes are 1.42e-7 and 7.81e-7 s per step: 3.2e-10 s per mode
//  and load, and the rest a step's own cost (recording, envelopes): 9e-8 s
//  on this path, 6.4e-8 s on the workers' batched path (`vsi work` of the
//  HSLM example: 0.20 s process CPU for 3.1e6 steps of 3 modes x ~45
//  loads), so 5e-8 s. What a run costs before its first step (sampling
//  the modes under the axles: 0.4 and 19 ms) goes with the basis: 2.5e-6 s
//  per DOF and mode in all. Measured / predicted then 0.70-1.63 on the
//  bench (its band: 0.5-2), and 0.73 (HSLM example, 330 jobs) and 1.11 (the
//  viaduct, HSLM-A1/A5/A10 at 200-400 km/h, 15 jobs) for `vsi work`'s
//  process CPU (user + sys) against the study's estimate (before: 0.32
//  and 0.39).
struct Coefficients {
  double mf_per_dof = 3.2e-8;
  double axle = 2.5e-8;
  double interaction_per_dof = 5.5e-8;
  double factor_per_dof = 1.0e-5;
  double flexibility_per_rail_dof_dof = 7.0e-9;
  double modal_step = 5.0e-8;
  double mode_per_load = 3.2e-10;
  double basis_per_dof_mode = 2.5e-6;
};
constexpr Coefficients kFit;

}  // namespace

CostInputs cost_inputs(const Scene& scene, bool modal, int modes) {
  CostInputs in;
  in.modal = modal;
  in.interaction = !scene.train.is_moving_forces();
  in.steps = static_cast<double>(planned_steps(scene));
  in.structure_dofs = scene.structure->num_dofs();
  in.rail_dofs = static_cast<double>(scene.structure->rail_dofs().size());
  const double lines = static_cast<double>(scene.analysis.contact.rail_lines.size());
  in.axles = static_cast<double>(scene.train.moving_forces.size()) * lines;
  in.modes = modes;
  in.output_points = static_cast<double>(scene.structure->outputs().size());
  return in;
}

CostPrediction predict_cost(const CostInputs& in) {
  const Coefficients& c = kFit;
  CostPrediction p;
  if (in.modal) {
    p.setup_cpu_s = c.basis_per_dof_mode * in.structure_dofs * in.modes;
    p.loop_cpu_s = in.steps * (c.modal_step + c.mode_per_load * in.modes * (in.axles + in.output_points));
    return p;
  }
  p.setup_cpu_s = c.factor_per_dof * in.structure_dofs +
                  (in.interaction ? c.flexibility_per_rail_dof_dof * in.rail_dofs * in.structure_dofs : 0.0);
  p.loop_cpu_s = in.steps * (in.interaction ? c.interaction_per_dof * in.structure_dofs
                                            : c.mf_per_dof * in.structure_dofs + c.axle * in.axles);
  return p;
}

std::string describe_cost_model() {
  const Coefficients& c = kFit;
  return fmt::format(
      "FE: setup {:.3g} s x DOFs (+ {:.3g} s x rail DOFs x DOFs with contact), per step {:.3g} s x DOFs with "
      "contact, else {:.3g} s x DOFs + {:.3g} s x axles; modal: setup {:.3g} s x DOFs x modes, per step {:.3g} s + "
      "{:.3g} s x modes x (axles + output points)",
      c.factor_per_dof, c.flexibility_per_rail_dof_dof, c.interaction_per_dof, c.mf_per_dof, c.axle,
      c.basis_per_dof_mode, c.modal_step, c.mode_per_load);
}

}  // namespace railvsi
