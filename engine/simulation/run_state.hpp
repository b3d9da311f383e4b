#pragma once
// All mutable state of one run (the "context" to the Simulation's "system"):
// kinematic states of structure and vehicles, the contact forces and loads
// of the last step, scratch vectors, and the envelope accumulators.
#include <optional>
#include <vector>

#include "integration/history_operator.hpp"
#include "simulation/result.hpp"
#include "simulation/rigid_wheels.hpp"
#include "simulation/run_monitor.hpp"
#include "simulation/scene.hpp"
#include "simulation/deck_twist.hpp"
#include "simulation/evaluation_window.hpp"
#include "simulation/modal_section_forces.hpp"
#include "simulation/section_forms.hpp"
#include "simulation/static_equilibrium.hpp"
#include "simulation/step_solver.hpp"

namespace railvsi {

class RunState {
 public:
  // `coords`: the structure coordinates of the step solver (and of
  // statics.u_s), `section_forms` (of the FE DOFs), `twist` (the deck twist
  // gauge) and `modal_sections` (on the modal structure: the same forms on
  // its modes, evaluated by mode acceleration; null on the FE structure):
  // referenced, not copied.
  RunState(const Scene& scene, const TrainLayout& layout, const StaticState& statics, double start_x_m,
           const StructureCoordinates& coords, const SectionForms& section_forms, const DeckTwistGauge& twist,
           const ModalSectionForces* modal_sections = nullptr);

  // Advance from t_n to t_new = t_n + dt.
  Status step(const HhtCoefficients& h, double t_new, StepSolver& solver, int& iterations);
  // Update the envelopes with the current state; append to the histories
  // when `store`.
  void record(long step_index, double t_s, Histories& histories, bool store);
  void summarize(RunSummary& summary) const;
  const RunMonitor& monitor() const { return *monitor_; }

 private:
  double front_x(double t_s) const { return start_x_m_ + scene_.speed_mps * t_s; }
  bool in_window(double front_x_m, const ContactSpec& c) const;
  void record_sections(double front_x_m);

  const Scene& scene_;
  const TrainLayout& layout_;
  const StructureCoordinates& coords_;
  double start_x_m_;
  SparseHistoryOperator history_;  // the structure's M, C, K fused for the HHT history terms
  // The history terms of the current state s_ and its products (K u, C v,
  // M v, M a) for the energy balance, from one pass after each step.
  bool history_ready_ = false;
  StateProducts products_;
  KinematicState s_;
  std::vector<KinematicState> vehicles_;  // one per vehicle instance
  std::vector<Vector> vehicle_rhs_, vehicle_work_;
  Vector P_;    // contact forces at t_n
  Vector Q0_;   // static wheel loads
  Vector f_s_;  // total structure load at t_n
  std::vector<std::optional<RailContactRow>> rows_;
  Vector r_, rhs_s_, rhs_v_, f_new_;
  std::vector<std::size_t> irregularity_hint_;  // each wheel's last sample interval (Irregularity::at)
  StepSolution solution_;
  RigidWheels rigid_;
  // The state at t_n while stepping (for the monitor's energy balance).
  KinematicState s_old_;
  std::vector<KinematicState> vehicles_old_;
  Vector P_old_, f_s_old_;
  std::optional<RunMonitor> monitor_;
  // Envelopes, updated every step (not only at stored samples).
  std::vector<double> max_abs_u_, max_abs_a_, min_P_, no_contact_s_;
  double max_abs_body_a_ = 0.0;
  // The wheels under each car body (train_layout.hpp).
  std::vector<BodyWheels> body_wheels_;
  std::vector<bool> contact_in_window_;
  EvaluationWindow window_;
  // Section forces of a beam deck (empty forms otherwise).
  const SectionForms& sections_;
  const ModalSectionForces* modal_sections_;
  SectionEnvelope section_envelope_;
  std::vector<DeckLoad> deck_loads_;
  std::vector<double> section_values_;
  // Deck twist (no gauge on a plane model).
  const DeckTwistGauge& twist_;
  std::vector<double> twist_scratch_;
  double max_abs_twist_m_ = 0.0, twist_x_m_ = 0.0;
};

}  // namespace railvsi
