#include "planning/cost_model.hpp"

#include <cmath>

#include <fmt/format.h>

#include "simulation/simulation.hpp"
#include "solver/hybrid_basis.hpp"

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
// The hybrid structure, fitted by hand on tests/bench/hybrid_bench --cost
// (2026-11-27 22:27-22:40 UTC, thread CPU, one thread, load 3-6):
// generated 3D decks of 6,042 / 19,869 / 50,208 / 233,137 DOFs (interior
// n_i 3,729 / 17,205 / 47,328 / 230,009, interface n_g 189 / 540 / 756 /
// 1,004, the same 2,124 track DOFs), ICE3, 1,000 steps, cut-offs 100 and
// 221 Hz (18-84 modes). The factor of a deck's interior and a solve on it
// grow as n_i^1.25 there (constraint modes 5.6-7.2e-9 s x n_i^1.25 x n_g);
// the interior's modes as n_i^1.25 x (m + 20) (a slice's Lanczos start
// and its count factor: 1.2-3.0e-7 s); the reduction's dense products as
// n_i x (n_g + m)^2 (4.3-5.0e-11 s); a dt's own setup (0.19-1.88 s) as
// the rail flexibility on the reduced operator plus a part growing as
// n_i^1.25 (1.5-3.3e-7 s; not separated further); a step as (n_g + m)^2
// (8e-10 s) plus
// what the track, the wheels and the envelopes cost on every deck (0.36
// ms a step for ICE3's 32 wheels on 2,124 track DOFs: one track size
// cannot separate them, so it is put on the track DOFs).
// Refitted 2026-11-28 (04:16-04:28 UTC, load 10-12) for the free-interface
// basis with one factor of the bridge, interface last: hybrid_bench 6000
// 20000 50000 --cost --cutoffs 110 and 233292 --cutoffs 108.9 (45-48
// modes); constraint modes 0.05 / 0.54 / 2.32 / 22.42 s (x 0.77 of the old
// term at 50k and seed scale), modes 0.32 / 1.88 / 5.13 / 35.74 s (x 0.73-
// 0.75), reduction 0.02 / 0.31 / 1.33 / 11.62 s (the old term, kept).
struct Coefficients {
  double mf_per_dof = 3.2e-8;
  double axle = 2.5e-8;
  double interaction_per_dof = 5.5e-8;
  double factor_per_dof = 1.0e-5;
  double flexibility_per_rail_dof_dof = 7.0e-9;
  double modal_step = 5.0e-8;
  double mode_per_load = 3.2e-10;
  double basis_per_dof_mode = 2.5e-6;
  double hybrid_psi = 4.5e-9;            // x n_i^1.25 x n_g
  double hybrid_interior_mode = 1.1e-7;  // x n_i^1.25 x (modes + 20)
  double hybrid_modes_start = 20.0;
  double hybrid_reduce = 4.7e-11;        // x n_i x (n_g + modes)^2
  double hybrid_flexibility = 4.0e-8;    // x rail DOFs x (n_t + n_g + modes), per dt
  double hybrid_dense_factor = 1.5e-10;  // x (n_g + modes)^3, per dt
  double hybrid_dt_interior = 3.0e-7;    // x n_i^1.25, per dt
  double hybrid_dense_step = 8.0e-10;    // x (n_g + modes)^2, per step
  double hybrid_track_step = 1.7e-7;     // x n_t, per step
};
constexpr Coefficients kFit;

}  // namespace

CostInputs cost_inputs(const Scene& scene, StructureBackend backend, int modes) {
  CostInputs in;
  in.modal = backend == StructureBackend::kModal;
  in.hybrid = backend == StructureBackend::kHybrid;
  in.interaction = !scene.train.is_moving_forces();
  in.steps = static_cast<double>(planned_steps(scene));
  in.structure_dofs = scene.structure->num_dofs();
  in.rail_dofs = static_cast<double>(scene.structure->rail_dofs().size());
  const double lines = static_cast<double>(scene.analysis.contact.rail_lines.size());
  in.axles = static_cast<double>(scene.train.moving_forces.size()) * lines;
  in.modes = modes;
  in.output_points = static_cast<double>(scene.structure->outputs().size());
  if (in.hybrid) {
    const HybridPartition p = hybrid_partition(*scene.structure);
    in.track_dofs = p.track_dofs;
    in.interface_dofs = p.interface_dofs;
    in.interior_dofs = p.interior_dofs;
  }
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
  if (in.hybrid) {
    const double n_i = in.interior_dofs, dense = in.interface_dofs + in.modes;
    const double factor_scale = std::pow(n_i, 1.25);
    p.structure_setup_cpu_s = c.hybrid_psi * factor_scale * in.interface_dofs +
                              (n_i > 0.0 ? c.hybrid_interior_mode * factor_scale * (in.modes + c.hybrid_modes_start)
                                         : 0.0) +
                              c.hybrid_reduce * n_i * dense * dense;
    // Per dt: the reduced operator's factor (its dense block) and the rail
    // flexibility on it.
    p.setup_cpu_s = p.structure_setup_cpu_s + c.hybrid_dense_factor * dense * dense * dense +
                    c.hybrid_flexibility * in.rail_dofs * (in.track_dofs + dense) +
                    c.hybrid_dt_interior * factor_scale;
    p.loop_cpu_s = in.steps * (c.hybrid_dense_step * dense * dense + c.hybrid_track_step * in.track_dofs);
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
      "{:.3g} s x modes x (axles + output points); hybrid (i interior, g interface, t track DOFs, m bridge modes): "
      "setup ({:.3g} s x g + {:.3g} s x (m + {:g})) x i^1.25 + {:.3g} s x i x (g + m)^2 once per structure, + {:.3g} s "
      "x (g + m)^3 + {:.3g} s x rail DOFs x (t + g + m) + {:.3g} s x i^1.25 per dt, per step {:.3g} s x (g + m)^2 + {:.3g} s x t",
      c.factor_per_dof, c.flexibility_per_rail_dof_dof, c.interaction_per_dof, c.mf_per_dof, c.axle,
      c.basis_per_dof_mode, c.modal_step, c.mode_per_load, c.hybrid_psi, c.hybrid_interior_mode, c.hybrid_modes_start,
      c.hybrid_reduce, c.hybrid_dense_factor, c.hybrid_flexibility, c.hybrid_dt_interior, c.hybrid_dense_step, c.hybrid_track_step);
}

}  // namespace railvsi
