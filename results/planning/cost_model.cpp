#include "planning/cost_model.hpp"

#include <fmt/format.h>

#include "simulation/simulation.hpp"

namespace railvsi {
namespace {

// Seconds of one core; see the header for the fit.
struct Coefficients {
  double solve_per_dof = 1.0e-8;
  double contact_squared = 5.0e-8;
  double axle = 5.0e-8;
  double factor_per_dof = 2.0e-6;
  double flexibility_per_rail_dof_dof = 2.0e-8;
  double mode_per_load = 1.0e-8;
  double basis_per_dof_mode = 1.0e-6;
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
  for (const TrainVehicle& v : scene.train.vehicles) in.contacts += static_cast<double>(v.model->wheels().size()) * lines;
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
    p.loop_cpu_s = in.steps * c.mode_per_load * in.modes * (in.axles + in.output_points);
    return p;
  }
  const double solves = in.interaction ? 2.0 : 1.0;
  p.setup_cpu_s = c.factor_per_dof * in.structure_dofs +
                  (in.interaction ? c.flexibility_per_rail_dof_dof * in.rail_dofs * in.structure_dofs : 0.0);
  p.loop_cpu_s = in.steps * (c.solve_per_dof * in.structure_dofs * solves + c.contact_squared * in.contacts * in.contacts +
                             c.axle * in.axles);
  return p;
}

std::string describe_cost_model() {
  const Coefficients& c = kFit;
  return fmt::format(
      "FE: setup {:.3g} s x DOFs (+ {:.3g} s x rail DOFs x DOFs with contact), per step {:.3g} s x DOFs x solves "
      "(2 with contact, else 1) + {:.3g} s x contacts^2 + {:.3g} s x axles; modal: setup {:.3g} s x DOFs x modes, per "
      "step {:.3g} s x modes x (axles + output points)",
      c.factor_per_dof, c.flexibility_per_rail_dof_dof, c.solve_per_dof, c.contact_squared, c.axle,
      c.basis_per_dof_mode, c.mode_per_load);
}

}  // namespace railvsi
