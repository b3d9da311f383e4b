#pragma once
// The CPU time of a run predicted before it runs, from the sizes a scene
// fixes (README "What accuracy costs"):
//
//   cpu = setup + steps x per_step
//   FE, per step:    c_int x n_s (interaction: two structure solves, the
//                    contact problem folded in) or c_mf x n_s + c_axle x n_a
//                    (moving forces); n_s structure DOFs: one pass over a
//                    banded factor costs ~ n_s
//   FE, setup:       c_factor x n_s + c_flex x n_rail x n_s (interaction:
//                    one solve per rail DOF for the rail flexibility)
//   modal, per step: c_step + c_mode x modes x (n_a + n_points)
//   modal, setup:    c_basis x n_s x modes (the modes, and the modes
//                    sampled under the axles before the first step)
//   hybrid, setup:   c_psi x n_i^1.25 x n_g (the interior's factor and a
//                    solve per interface DOF; a 3D deck's factor grows so)
//                    + c_imodes x n_i^1.25 x (modes + 20) (the interior's
//                    modes: Lanczos solves on that factor) + c_reduce x
//                    n_i x (n_g + modes)^2 (the reduction's dense
//                    products): once per structure; per dt c_dfactor x
//                    (n_g + modes)^3 + c_hflex x n_rail x (n_t + n_g +
//                    modes) + c_hdt x n_i^1.25 (the reduced operator's
//                    factor, rail flexibility, the rest)
//   hybrid, per step: c_dense x (n_g + modes)^2 (the reduced operator's
//                    dense block) + c_track x n_t (the track in FE)
//
// The coefficients (cost_model.cpp) were fitted on two README scenes
// measured by `vsi price` itself, the modal ones re-measured by
// tests/bench/cost_model_bench; `vsi price` prints predicted against
// measured for every run, which is how a user sees whether the model
// holds for a scene. A plane model has a banded factor; a 3D deck's factor
// is denser and the prediction then low: treat it as an order of
// magnitude.
#include <string>

#include "simulation/scene.hpp"

namespace railvsi {

struct CostInputs {
  bool modal = false;        // the structure's modes instead of the FE operator
  bool hybrid = false;       // the track in FE, the bridge in its modes
  bool interaction = false;  // multibody train with contact
  double steps = 0.0;
  double structure_dofs = 0.0;
  double rail_dofs = 0.0;
  double axles = 0.0;  // moving forces
  double modes = 0.0;  // modal: the structure's; hybrid: the bridge interior's
  double output_points = 0.0;
  // The hybrid structure's partition (HybridPartition).
  double track_dofs = 0.0;
  double interface_dofs = 0.0;
  double interior_dofs = 0.0;
};

struct CostPrediction {
  double setup_cpu_s = 0.0;
  // Of the setup, what does not depend on dt (the hybrid structure's
  // reduction, shared by every dt of a structure); the rest is per dt.
  double structure_setup_cpu_s = 0.0;
  double loop_cpu_s = 0.0;
  double total_cpu_s() const { return setup_cpu_s + loop_cpu_s; }
};

// Sizes of a scene as run on `backend` (planned_steps for the steps);
// `modes` for a modal run or the hybrid structure's bridge (0 otherwise).
CostInputs cost_inputs(const Scene& scene, StructureBackend backend, int modes = 0);
CostPrediction predict_cost(const CostInputs& inputs);
// "setup c_factor x n_s ... + steps x ..." with the numbers, for a person.
std::string describe_cost_model();

}  // namespace railvsi
