#include "simulation/run_state.hpp"

#include <algorithm>
#include <utility>
#include <cmath>
#include <fmt/format.h>
#include <limits>

namespace railvsi {

RunState::RunState(const Scene& scene, const TrainLayout& layout, const StaticState& statics,
                   double start_x_m, const StructureCoordinates& coords, const SectionForms& section_forms,
                   const DeckTwistGauge& twist, const ModalSectionForces* modal_sections)
    : scene_(scene), layout_(layout), coords_(coords), start_x_m_(start_x_m),
      history_(coords.M(), coords.C(), coords.K()), rigid_(scene, layout, coords),
      window_(EvaluationWindow::of(scene)), sections_(section_forms), modal_sections_(modal_sections),
      section_envelope_(section_forms), twist_(twist) {
  const int ns = coords.size();
  s_.resize(ns);
  s_.u = statics.u_s;
  for (const VehicleInstance& vi : layout.vehicles) {
    KinematicState k;
    k.resize(vi.model->num_dofs());
    k.u = statics.u_v.segment(vi.first_dof, vi.model->num_dofs());
    vehicles_.push_back(std::move(k));
    vehicle_rhs_.emplace_back(vi.model->num_dofs());
    vehicle_work_.emplace_back(vi.model->num_dofs());
  }
  const auto nc = static_cast<Eigen::Index>(layout.contacts.size());
  P_ = nc > 0 ? statics.P : Vector();
  Q0_ = P_;
  f_s_ = Vector::Zero(ns);
  add_moving_force_loads(scene, start_x_m, f_s_, coords);
  rows_ = locate_contacts(*scene.structure, layout, start_x_m);
  add_rail_loads(rows_, P_, 1.0, f_s_, coords);
  rigid_.follow_rail(start_x_m, s_, rows_, vehicles_);
  r_ = Vector::Zero(nc);
  const std::size_t np = scene.structure->outputs().size();
  max_abs_u_.assign(np, 0.0);
  max_abs_a_.assign(np, 0.0);
  min_P_.assign(static_cast<std::size_t>(nc), std::numeric_limits<double>::infinity());
  no_contact_s_.assign(static_cast<std::size_t>(nc), 0.0);
  monitor_.emplace(scene, layout, coords, start_x_m, s_, vehicles_, f_s_, P_);
  body_wheels_ = body_wheels(layout);
}

bool RunState::in_window(double front_x_m, const ContactSpec& c) const {
  return window_.contains(TrainLayout::position_m(front_x_m, c.offset_m));
}

Status RunState::step(const HhtCoefficients& h, double t_new, StepSolver& solver, int& iterations) {
  const double x = front_x(t_new);
  // Loads known at t_{n+1}: moving forces and the irregularity under each wheel.
  f_new_.setZero(s_.u.size());
  add_moving_force_loads(scene_, x, f_new_, coords_);
  rows_ = locate_contacts(*scene_.structure, layout_, x);
  irregularity_hint_.resize(static_cast<std::size_t>(r_.size()), 0);
  for (Eigen::Index c = 0; c < r_.size(); ++c)
    r_[c] = scene_.irregularity ? scene_.irregularity->at(TrainLayout::position_m(x, layout_.contacts[c].offset_m),
                                                          irregularity_hint_[static_cast<std::size_t>(c)])
                                : 0.0;
  rigid_.prepare(h, x, s_, vehicles_, rows_, r_);

  // Right-hand sides of eq. (3) with the new contact forces left out:
  // (1+alpha) F_{n+1} - alpha F_n + history terms.
  if (!history_ready_) history_.apply(h, s_, rhs_s_);
  history_ready_ = false;
  rhs_s_ += (1.0 + h.alpha) * f_new_ - h.alpha * f_s_;
  rhs_v_.resize(layout_.num_vehicle_dofs);
  for (std::size_t i = 0; i < layout_.vehicles.size(); ++i) {
    const VehicleInstance& vi = layout_.vehicles[i];
    hht_history_rhs(h, vi.model->M(), vi.model->C(), vi.model->K(), vehicles_[i], vehicle_rhs_[i],
                    vehicle_work_[i]);
    rhs_v_.segment(vi.first_dof, vi.model->num_dofs()) = vehicle_rhs_[i];
  }
  rhs_v_ += layout_.gravity_load_N;
  for (Eigen::Index c = 0; c < P_.size(); ++c) rhs_v_[layout_.contacts[c].global_dof] -= h.alpha * P_[c];

  solution_.P = P_;
  const StepProblem problem{rhs_s_, rhs_v_, rows_, r_, rigid_.enabled() ? &rigid_.terms() : nullptr};
  Status st = solver.solve(problem, solution_);
  iterations = solution_.iterations;
  if (!st.ok()) return st;
  if (!solution_.u_s.allFinite() || !solution_.u_v.allFinite() || !solution_.P.allFinite())
    return {StatusCode::kDiverged, "non-finite displacements or contact forces"};
  const double u_max = solution_.u_s.size() ? solution_.u_s.cwiseAbs().maxCoeff() : 0.0;
  if (u_max > 1e3)
    return {StatusCode::kDiverged, fmt::format("structure displacement {:.3e} m: the solution diverged", u_max)};

  // The state at t_n moves to s_old_ (a swap, no copy) and the new one is
  // written from it.
  std::swap(s_old_, s_);
  vehicles_old_ = vehicles_;
  P_old_ = P_;
  f_s_old_.swap(f_s_);
  hht_update(h, solution_.u_s, s_old_, s_);
  // The next step's history terms now, in the pass that also gives the
  // energy balance its products of the new state.
  history_.apply(h, s_, rhs_s_, &products_);
  history_ready_ = true;
  for (std::size_t i = 0; i < layout_.vehicles.size(); ++i)
    hht_update(h, solution_.u_v.segment(layout_.vehicles[i].first_dof, layout_.vehicles[i].model->num_dofs()),
               vehicles_[i]);
  rigid_.follow_rail(x, s_, rows_, vehicles_, /*after_step=*/true, t_new);
  P_ = solution_.P;
  f_s_.swap(f_new_);  // f_new_ is set anew at the next step
  add_rail_loads(rows_, P_, 1.0, f_s_, coords_);
  return monitor_->after_step(h, t_new, s_old_, s_, vehicles_old_, vehicles_, f_s_old_, f_s_, P_old_, P_, iterations,
                              &products_);
}

void RunState::record(long step_index, double t_s, Histories& hist, bool store) {
  const auto& outputs = scene_.structure->outputs();
  const double dt = scene_.analysis.dt_s;
  for (std::size_t p = 0; p < outputs.size(); ++p) {
    max_abs_u_[p] = std::max(max_abs_u_[p], std::abs(coords_.at(outputs[p].dof, s_.u)));
    max_abs_a_[p] = std::max(max_abs_a_[p], std::abs(coords_.at(outputs[p].dof, s_.a)));
  }
  const double x = front_x(t_s);
  if (sections_.available()) record_sections(x);
  if (twist_.available()) {
    double at = 0.0;
    const double t = max_abs_twist_m(twist_, s_.u, coords_, twist_scratch_, &at);
    if (t > max_abs_twist_m_ || step_index == 0) {
      max_abs_twist_m_ = t;
      twist_x_m_ = at;
    }
  }
  std::vector<bool>& contact_in = contact_in_window_;
  contact_in.assign(static_cast<std::size_t>(P_.size()), false);
  for (Eigen::Index c = 0; c < P_.size(); ++c) {
    const ContactSpec& cs = layout_.contacts[c];
    if (!in_window(x, cs)) continue;
    contact_in[static_cast<std::size_t>(c)] = true;
    min_P_[c] = std::min(min_P_[c], P_[c]);
    // A bilateral law holds the wheel on the rail in tension: that is not a
    // loss of contact (the monitor warns tensile_contact instead).
    if (step_index > 0 && P_[c] <= 0.0 && cs.law->unilateral()) no_contact_s_[c] += dt;
  }
  for (const BodyWheels& b : body_wheels_)
    if (std::any_of(b.contacts.begin(), b.contacts.end(),
                    [&](Eigen::Index c) { return contact_in[static_cast<std::size_t>(c)]; }))
      max_abs_body_a_ = std::max(max_abs_body_a_, std::abs(vehicles_[b.vehicle].a[b.dof]));
  if (!store) return;

  if (hist.t_s.empty()) {  // first sample: names and columns
    for (const auto& o : outputs) hist.point_names.push_back(o.name);
    hist.deck_displacement_m.resize(outputs.size());
    hist.deck_acceleration_mps2.resize(outputs.size());
    for (const ContactSpec& c : layout_.contacts)
      hist.wheel_names.push_back(wheel_name(c));
    hist.contact_force_N.resize(layout_.contacts.size());
    for (std::size_t v = 0; v < layout_.vehicles.size(); ++v)
      for (std::size_t b = 0; b < layout_.vehicles[v].model->body_dofs().size(); ++b)
        hist.body_names.push_back(b == 0 ? fmt::format("v{}_body", v + 1) : fmt::format("v{}_body{}", v + 1, b + 1));
    hist.carbody_acceleration_mps2.resize(hist.body_names.size());
  }
  hist.t_s.push_back(t_s);
  for (std::size_t p = 0; p < outputs.size(); ++p) {
    hist.deck_displacement_m[p].push_back(coords_.at(outputs[p].dof, s_.u));
    hist.deck_acceleration_mps2[p].push_back(coords_.at(outputs[p].dof, s_.a));
  }
  for (Eigen::Index c = 0; c < P_.size(); ++c) hist.contact_force_N[c].push_back(P_[c]);
  std::size_t b = 0;
  for (std::size_t v = 0; v < layout_.vehicles.size(); ++v)
    for (int d : layout_.vehicles[v].model->body_dofs())
      hist.carbody_acceleration_mps2[b++].push_back(vehicles_[v].a[d]);
}

void RunState::record_sections(double front_x_m) {
  const auto& rails = scene_.analysis.contact.rail_lines;
  const double share = 1.0 / static_cast<double>(rails.size());
  if (modal_sections_) {
    // Mode acceleration: the exact static value under the loads on the
    // rails (moving forces, contact forces) plus the modes' dynamic part
    // under the modal loads of the same loads (f_s_, of this step).
    const SectionInfluence& statics = modal_sections_->statics();
    section_values_.assign(sections_.forms.size(), 0.0);
    for (int r : rails)
      for (const MovingForce& m : scene_.train.moving_forces)
        statics.add_form_values(r, TrainLayout::position_m(front_x_m, m.offset_m), share * m.load_N, section_values_);
    for (Eigen::Index c = 0; c < P_.size(); ++c) {
      const ContactSpec& cs = layout_.contacts[c];
      statics.add_form_values(cs.rail_line, TrainLayout::position_m(front_x_m, cs.offset_m), P_[c], section_values_);
    }
    modal_sections_->add_dynamic_part(s_.u.data(), s_.v.data(), s_.a.data(), f_s_.data(), section_values_.data());
    section_envelope_.update(section_values_);
    return;
  }
  // FE: the forms of the state, plus the direct term of the loads standing
  // on the deck line itself (a deck without track): the moving forces or
  // the contact forces of the wheels on it.
  const RailLine& deck = scene_.structure->info().deck_line;
  deck_loads_.clear();
  const auto add_load = [&](double x_m, double down_N) {
    if (deck.covers(x_m)) deck_loads_.push_back({x_m, down_N});
  };
  for (int r : rails)
    if (sections_.rail_is_deck[static_cast<std::size_t>(r)])
      for (const MovingForce& m : scene_.train.moving_forces)
        add_load(TrainLayout::position_m(front_x_m, m.offset_m), share * m.load_N);
  for (Eigen::Index c = 0; c < P_.size(); ++c) {
    const ContactSpec& cs = layout_.contacts[c];
    if (sections_.rail_is_deck[static_cast<std::size_t>(cs.rail_line)])
      add_load(TrainLayout::position_m(front_x_m, cs.offset_m), P_[c]);
  }
  section_values_.resize(sections_.forms.size());
  for (std::size_t f = 0; f < sections_.forms.size(); ++f)
    section_values_[f] = sections_.forms[f].state_value(s_.u, s_.v, s_.a) + sections_.forms[f].load_value(deck, deck_loads_);
  section_envelope_.update(section_values_);
}

void RunState::summarize(RunSummary& sum) const {
  const auto& outputs = scene_.structure->outputs();
  sum.points.clear();
  for (std::size_t p = 0; p < outputs.size(); ++p) {
    sum.points.push_back({outputs[p].name, outputs[p].x_m, max_abs_u_[p], max_abs_a_[p], std::nullopt, std::nullopt});
    sum.max_abs_displacement_m = std::max(sum.max_abs_displacement_m, max_abs_u_[p]);
    sum.max_abs_acceleration_mps2 = std::max(sum.max_abs_acceleration_mps2, max_abs_a_[p]);
  }
  // No wheel inside the evaluation window (or no wheels): no wheel values.
  constexpr double kNone = std::numeric_limits<double>::quiet_NaN();
  sum.min_contact_force_N = kNone;
  sum.max_unloading_ratio = kNone;
  sum.contact_loss_s = kNone;
  if (!min_P_.empty()) {
    for (std::size_t c = 0; c < min_P_.size(); ++c) {
      const ContactSpec& cs = layout_.contacts[c];
      WheelSummary w;
      w.name = wheel_name(cs);
      w.static_load_N = Q0_[static_cast<Eigen::Index>(c)];
      w.evaluated = std::isfinite(min_P_[c]);
      if (w.evaluated) {
        w.min_force_N = min_P_[c];
        w.unloading_ratio = w.static_load_N > 0.0 ? (w.static_load_N - min_P_[c]) / w.static_load_N : 0.0;
        w.contact_loss_s = no_contact_s_[c];
      }
      sum.wheels.push_back(w);
      if (!w.evaluated) continue;  // never in the evaluation window
      if (std::isnan(sum.min_contact_force_N)) {  // the first evaluated wheel
        sum.min_contact_force_N = std::numeric_limits<double>::infinity();
        sum.max_unloading_ratio = sum.contact_loss_s = 0.0;
      }
      sum.min_contact_force_N = std::min(sum.min_contact_force_N, min_P_[c]);
      const double q0 = Q0_[static_cast<Eigen::Index>(c)];
      if (q0 > 0.0) sum.max_unloading_ratio = std::max(sum.max_unloading_ratio, (q0 - min_P_[c]) / q0);
      sum.contact_loss_s = std::max(sum.contact_loss_s, no_contact_s_[c]);
    }
  }
  section_envelope_.summarize(sum);
  if (twist_.available()) {
    sum.max_abs_deck_twist_m = max_abs_twist_m_;
    sum.deck_twist_x_m = twist_x_m_;
  } else {
    sum.deck_twist_note = twist_.unavailable;
  }
  monitor_->summarize(sum);
  sum.max_abs_carbody_acceleration_mps2 = max_abs_body_a_;
  rigid_.add_warnings(sum.warnings);
}

}  // namespace railvsi
