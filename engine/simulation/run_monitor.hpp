#pragma once
// The health of one run (README "Run health"): watches every step for what
// makes numbers that converged step by step still not a result, and
// collects the warnings a user must see beside them.
//   instability (status "unstable"): a contact force oscillating at the
//     Nyquist frequency (chatter), a structure or vehicle displacement
//     implausible for the structure, the energy balance broken;
//   warnings: energy_balance, tensile_contact (inside the evaluation
//     window), newton_iterations_high, irregularity_ignored,
//     entry_inside_window, exit_inside_window, modal_interaction_unverified.
// Part of the per-run state: one monitor per run.
#include <optional>
#include <vector>

#include "simulation/energy_balance.hpp"
#include "simulation/evaluation_window.hpp"
#include "simulation/result.hpp"
#include "simulation/scene.hpp"
#include "simulation/train_layout.hpp"
#include "solver/structure_coordinates.hpp"

namespace railvsi {

struct MonitorLimits {
  // A contact force whose increment changes sign with |dP| > this fraction
  // of the static load for this many consecutive steps chatters.
  double chatter_fraction = 0.25;
  int chatter_steps = 6;
  // Structure displacement beyond max(min_implausible_m, span / span_ratio)
  // and vehicle displacement from its static state beyond vehicle_limit are
  // not a bridge under a train any more.
  double min_implausible_m = 0.1;
  double span_ratio = 100.0;
  double vehicle_limit = 0.5;  // m or rad
  // Energy residual (relative): warning above, unstable above.
  double energy_warning = 1e-4;
  double energy_unstable = 5e-2;
};

// What a scene's inputs earn before it runs (inputs the run cannot honour):
// modal_interaction_unverified, irregularity_ignored. RunMonitor starts
// with them; the modal moving-force rung, which has no monitor, adds them
// itself.
std::vector<RunWarning> scene_input_warnings(const Scene& scene);

// The displacement beyond which a structure under a train is implausible:
// max(limits.min_implausible_m, bridge length / limits.span_ratio).
double implausible_displacement_m(const StructureModel& structure, const MonitorLimits& limits = {});

class RunMonitor {
 public:
  // Structure states and loads in the coordinates `coords` (referenced).
  RunMonitor(const Scene& scene, const TrainLayout& layout, const StructureCoordinates& coords, double start_x_m,
             const KinematicState& s0,
             const std::vector<KinematicState>& vehicles0, const Vector& f_s0, const Vector& P0,
             MonitorLimits limits = {});

  // After the step t_n -> t_new; `old` states at t_n, current ones at t_new,
  // total structure loads f_s (moving forces and rail loads of the contact
  // forces) and contact forces at both times. Not ok: the run is unstable.
  // structure_products: K u, C v, M v, M a of s when the caller has them
  // (their vectors are swapped into the energy account).
  Status after_step(const HhtCoefficients& h, double t_new, const KinematicState& s_old, const KinematicState& s,
                    const std::vector<KinematicState>& vehicles_old, const std::vector<KinematicState>& vehicles,
                    const Vector& f_s_old, const Vector& f_s_new, const Vector& P_old, const Vector& P_new,
                    int iterations, StateProducts* structure_products = nullptr);
  // Relative residual of the energy balance so far.
  double energy_residual() const;
  // Warnings and the energy residual into the summary.
  void summarize(RunSummary& summary) const;

 private:
  // Vehicle v's shifted load f^a (gravity and contact forces) into f.
  void vehicle_load(std::size_t v, const Vector& P_old, const Vector& P_new, double alpha, Vector& f) const;
  void warn_once(const std::string& code, std::string message, std::optional<double> t_s = {},
                 std::optional<int> wheel = {}, std::optional<double> factor = {});
  void check_track_ends(double start_x_m);

  const Scene& scene_;
  const TrainLayout& layout_;
  const StructureCoordinates& coords_;
  MonitorLimits limits_;
  double start_x_m_ = 0.0;
  EvaluationWindow window_;
  double u_limit_m_ = 0.0;
  std::vector<Vector> u_v0_;
  EnergyAccount<SparseMatrix> structure_energy_;
  std::vector<EnergyAccount<DenseMatrix>> vehicle_energy_;
  // False with rigid contact: its wheels are set from the rail's kinematics
  // after every step (rigid_wheels.hpp), a constraint the discrete HHT
  // energy balance of each subsystem does not contain.
  bool energy_checked_ = true;
  double max_residual_J_ = 0.0;
  double max_mechanical_change_J_ = 0.0;
  Vector Q0_;
  Vector dP_prev_;
  std::vector<int> alternations_;
  std::vector<double> min_tension_ratio_;  // most negative P/Q0 of a bilateral contact
  std::vector<RunWarning> warnings_;
  int max_iterations_ = 0;
  Vector f_alpha_;  // scratch: a subsystem's shifted load of the step
};

}  // namespace railvsi
