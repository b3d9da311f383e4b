#pragma once
// One HHT step of the coupled system with the contact forces of the new step
// unknown. Two backends solve the same discrete equations:
//   condensed (production): structure and vehicles eliminated, Newton on the
//     contact forces only, CHOLMOD factor reused;
//   reference: eq. (36) assembled literally and solved by UMFPACK at every
//     Newton iteration (small models, verification).
#include <memory>
#include <optional>
#include <vector>

#include "core/status.hpp"
#include "model/rail_line.hpp"
#include "simulation/rigid_wheels.hpp"
#include "simulation/train_layout.hpp"
#include "solver/structure_operator.hpp"

namespace railvsi {

// K_bar_s u_s = rhs_s - (1+alpha) sum_c N_c^T P_c
// K_bar_v u_v = rhs_v + (1+alpha) sum_c E_c^T P_c
// contact:  delta_c = N_c u_s + r_c - E_c u_v,  P_c = H_c(delta_c)
// Rigid contacts (rigid_wheels.hpp): delta_c = 0 and the vehicle equations
// carry - M E^T d_a - (1+alpha) C E^T d_v, the wheel following the rail.
struct StepProblem {
  const Vector& rhs_s;
  const Vector& rhs_v;
  const std::vector<std::optional<RailContactRow>>& rows;
  const Vector& r;
  const std::vector<WheelFollowsRail>* rigid = nullptr;  // one per contact, or null
};

struct StepSolution {
  Vector u_s, u_v;
  Vector P;  // guess on entry
  int iterations = 0;
};

class StepSolver {
 public:
  virtual ~StepSolver() = default;
  virtual Status solve(const StepProblem& problem, StepSolution& solution) = 0;
};

struct StepSolverOptions {
  double alpha = 0.0;
  int max_iterations = 50;
  double tolerance = 1e-10;
  double force_scale_N = 1.0;
};

// Structure vectors in `coords` (op->coordinates(model); referenced, must
// outlive the solver).
std::unique_ptr<StepSolver> make_condensed_step_solver(
    std::shared_ptr<const StructureOperator> op, const StructureCoordinates& coords, const TrainLayout& layout,
    std::vector<VehicleOperator> vehicles, const StepSolverOptions& options);

std::unique_ptr<StepSolver> make_reference_step_solver(const StructureModel& structure,
                                                       const EffectiveMatrixFactors& factors,
                                                       const TrainLayout& layout,
                                                       const HhtCoefficients& h,
                                                       const StepSolverOptions& options);

}  // namespace railvsi
