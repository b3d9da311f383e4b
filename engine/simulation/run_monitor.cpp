#include "simulation/run_monitor.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <limits>

#include "model/undamped_structure.hpp"
#include "simulation/track_entry.hpp"

namespace railvsi {

RunMonitor::RunMonitor(const Scene& scene, const TrainLayout& layout, const StructureCoordinates& coords,
                       double start_x_m, const KinematicState& s0, const std::vector<KinematicState>& vehicles0,
                       const Vector& f_s0, const Vector& P0, MonitorLimits limits)
    : scene_(scene), layout_(layout), coords_(coords), limits_(limits), start_x_m_(start_x_m),
      window_(EvaluationWindow::of(scene)) {
  u_limit_m_ = implausible_displacement_m(*scene.structure, limits_);
  structure_energy_ = EnergyAccount<SparseMatrix>(coords.M(), coords.C(), coords.K(), s0, f_s0);
  for (std::size_t v = 0; v < layout.vehicles.size(); ++v) {
    const VehicleModel& m = *layout.vehicles[v].model;
    u_v0_.push_back(vehicles0[v].u);
    vehicle_load(v, P0, P0, 0.0, f_alpha_);
    vehicle_energy_.emplace_back(m.M(), m.C(), m.K(), vehicles0[v], f_alpha_);
  }
  for (const ContactSpec& c : layout.contacts)
    if (c.law->is_constraint()) energy_checked_ = false;
  Q0_ = P0;
  dP_prev_ = Vector::Zero(P0.size());
  alternations_.assign(static_cast<std::size_t>(P0.size()), 0);
  min_tension_ratio_.assign(static_cast<std::size_t>(P0.size()), 0.0);

  for (RunWarning& w : scene_input_warnings(scene)) warn_once(w.code, std::move(w.message));
  check_track_ends(start_x_m);
}

double implausible_displacement_m(const StructureModel& structure, const MonitorLimits& limits) {
  const auto [b0, b1] = bridge_extent_m(structure);
  return std::max(limits.min_implausible_m, (b1 - b0) / limits.span_ratio);
}

std::vector<RunWarning> scene_input_warnings(const Scene& scene) {
  std::vector<RunWarning> out;
  if (!scene.train.is_moving_forces() && scene.analysis.structure_backend == StructureBackend::kModal)
    out.push_back({"modal_interaction_unverified",
                   "interaction on the modes: its error against the FE structure depends on the track and the "
                   "cut-off and is not known for this scene (measured 0.07 % to 23 % on the filtered deck "
                   "acceleration and up to 10 % on the minimum contact force, docs/method.md \"The modal structure\"); "
                   "in a study, \"accuracy\": {\"verify\": \"governing\"} re-runs the governing jobs on the FE "
                   "structure",
                   {}, {}, {}});
  if (scene.train.is_moving_forces() && scene.irregularity)
    out.push_back({"irregularity_ignored",
                   "moving forces do not feel the track irregularity: it has no effect on this run (use a multibody "
                   "train for its effect)",
                   {}, {}, {}});
  // On every rung (the modal moving-force runs take these warnings too).
  if (structure_undamped(scene.structure->info()))
    out.push_back({"structure_undamped", std::string(kUndampedStructureWarning), {}, {}, {}});
  return out;
}

void RunMonitor::vehicle_load(std::size_t v, const Vector& P_old, const Vector& P_new, double alpha,
                              Vector& f) const {
  const VehicleInstance& vi = layout_.vehicles[v];
  f = layout_.gravity_load_N.segment(vi.first_dof, vi.model->num_dofs());
  for (std::size_t c = 0; c < layout_.contacts.size(); ++c) {
    const ContactSpec& cs = layout_.contacts[c];
    if (cs.vehicle != static_cast<int>(v)) continue;
    const auto i = static_cast<Eigen::Index>(c);
    f[cs.local_dof] += (1.0 + alpha) * P_new[i] - alpha * P_old[i];
  }
}

void RunMonitor::warn_once(const std::string& code, std::string message, std::optional<double> t_s,
                           std::optional<int> wheel, std::optional<double> factor) {
  for (const RunWarning& w : warnings_)
    if (w.code == code) return;
  warnings_.push_back({code, std::move(message), t_s, wheel, factor});
}

// The ends of the modelled track, where the model's transients are not a
// real track's. Results must not contain them.
void RunMonitor::check_track_ends(double start_x_m) {
  const StructureModel& st = *scene_.structure;
  if (!(scene_.speed_mps > 0.0)) return;
  std::vector<double> offsets;
  for (const MovingForce& m : scene_.train.moving_forces) offsets.push_back(m.offset_m);
  for (const ContactSpec& c : layout_.contacts) offsets.push_back(c.offset_m);
  if (std::optional<RunWarning> entry = track_entry_warning(scene_, offsets, start_x_m))
    warn_once(entry->code, std::move(entry->message), entry->t_s);
  const auto bridge_end = bridge_extent_m(st).second;

  // A wheel running off the exit rail end onto the rigid path beyond meets
  // a step in its support (on the 3 x 25 m viaduct with ICE3: +-0.7 MN on a
  // 150 kN wheel). The wheels under the same car body feel it: it is part of
  // the results when one of them is still inside the window at that moment.
  // Further along an articulated rake it has faded (Eurostar on the same
  // viaduct: no wheel, car-body or deck value changes by more than 4e-9
  // relative with the exit track 195 m instead of 40 m), and other vehicles
  // and the bridge 40 m away do not feel it. A moving force leaves
  // smoothly: the load's weight on the anchored end node is zero. Without
  // an exit track (the rail ends with the bridge) the exit is the bridge's
  // own.
  constexpr int kSameCarBody = 4;  // wheel, bogie, body, bogie, wheel
  for (std::size_t c = 0; c < layout_.contacts.size(); ++c) {
    const ContactSpec& leaving = layout_.contacts[c];
    const double rail_end = st.rails()[static_cast<std::size_t>(leaving.rail_line)].end_m();
    if (!(rail_end > bridge_end)) continue;
    const double front_m = rail_end + leaving.offset_m;  // front when this wheel leaves
    if (front_m < start_x_m) continue;  // starts past the rail end
    const VehicleModel& model = *layout_.vehicles[static_cast<std::size_t>(leaving.vehicle)].model;
    const std::vector<int> near = model.coupled_dofs(leaving.local_dof, kSameCarBody);
    for (const ContactSpec& other : layout_.contacts) {
      if (other.vehicle != leaving.vehicle || std::find(near.begin(), near.end(), other.local_dof) == near.end() ||
          !window_.contains(TrainLayout::position_m(front_m, other.offset_m)))
        continue;
      const double other_x_m = TrainLayout::position_m(front_m, other.offset_m);
      const std::string where =
          &other == &leaving ? fmt::format("x = {:.1f} m is", rail_end)
                             : fmt::format("wheel {} of its vehicle (x = {:.1f} m) is", wheel_name(other), other_x_m);
      warn_once("exit_inside_window",
                fmt::format("wheel {} leaves the modelled track at x = {:.1f} m, and {} inside the evaluation window "
                            "(to {:.1f} m): the exit transient is part of that vehicle's wheel and car-body results; "
                            "lengthen the exit track",
                            wheel_name(leaving), rail_end, where, window_.end_m),
                (front_m - start_x_m) / scene_.speed_mps, static_cast<int>(c));
      return;
    }
  }
}

Status RunMonitor::after_step(const HhtCoefficients& h, double t_new, const KinematicState& s_old,
                              const KinematicState& s, const std::vector<KinematicState>& vehicles_old,
                              const std::vector<KinematicState>& vehicles, const Vector& f_s_old,
                              const Vector& f_s_new, const Vector& P_old, const Vector& P_new, int iterations,
                              StateProducts* structure_products) {
  max_iterations_ = std::max(max_iterations_, iterations);
  // Energy.
  if (energy_checked_) {
    if (structure_products) {
      structure_energy_.step(h, s_old, s, f_s_new, f_s_old, *structure_products);
    } else {
      f_alpha_ = (1.0 + h.alpha) * f_s_new - h.alpha * f_s_old;
      structure_energy_.step(h, s_old, s, f_alpha_);
    }
    for (std::size_t v = 0; v < vehicle_energy_.size(); ++v) {
      vehicle_load(v, P_old, P_new, h.alpha, f_alpha_);
      vehicle_energy_[v].step(h, vehicles_old[v], vehicles[v], f_alpha_);
    }
    double residual = 0.0, mechanical = 0.0;
    const auto add = [&](const auto& account) {
      const EnergyTotals& e = account.totals();
      const double change = e.kinetic_J + e.strain_J - account.initial_mechanical_J();
      mechanical += change;
      residual += change + e.damping_J + e.hht_J - e.work_J;
    };
    add(structure_energy_);
    for (const auto& a : vehicle_energy_) add(a);
    max_residual_J_ = std::max(max_residual_J_, std::abs(residual));
    max_mechanical_change_J_ = std::max(max_mechanical_change_J_, std::abs(mechanical));
    if (energy_residual() > limits_.energy_unstable)
      return {StatusCode::kUnstable,
              fmt::format("the energy balance is broken (relative residual {:.2e}): the step equations did not hold",
                          energy_residual())};
  }

  // Displacements.
  const double u_max = coords_.max_abs_displacement(s.u);
  if (u_max > u_limit_m_)
    return {StatusCode::kUnstable,
            fmt::format("structure displacement {:.4g} m exceeds {:.4g} m (max(0.1 m, span/100)), "
                        "implausible for this structure",
                        u_max, u_limit_m_)};
  for (std::size_t v = 0; v < vehicles.size(); ++v) {
    const double dv = (vehicles[v].u - u_v0_[v]).cwiseAbs().maxCoeff();
    if (dv > limits_.vehicle_limit)
      return {StatusCode::kUnstable,
              fmt::format("vehicle {} moved {:.3g} (m or rad) from its static position: implausible", v + 1, dv)};
  }

  // Contact forces: chatter and tension.
  const double front_x_m = start_x_m_ + scene_.speed_mps * t_new;
  for (Eigen::Index c = 0; c < P_new.size(); ++c) {
    const double q0 = std::max(std::abs(Q0_[c]), 1.0);
    const double dP = P_new[c] - P_old[c];
    // A wheel past the exit rail end runs on the rigid path: it no longer
    // loads the structure, and its landing there (rigid contact at
    // alpha = -1/3 chatters) is no result. The free vibration after the
    // train has left runs every wheel off the rail end.
    const ContactSpec& spec = layout_.contacts[static_cast<std::size_t>(c)];
    if (TrainLayout::position_m(front_x_m, spec.offset_m) >
        scene_.structure->rails()[static_cast<std::size_t>(spec.rail_line)].end_m()) {
      alternations_[static_cast<std::size_t>(c)] = 0;
      dP_prev_[c] = dP;
      continue;
    }
    const double big = limits_.chatter_fraction * q0;
    auto& alt = alternations_[static_cast<std::size_t>(c)];
    alt = (std::abs(dP) > big && std::abs(dP_prev_[c]) > big && dP * dP_prev_[c] < 0.0) ? alt + 1 : 0;
    dP_prev_[c] = dP;
    if (alt >= limits_.chatter_steps) {
      warn_once("contact_chatter",
                fmt::format("contact force of wheel {} alternates step to step ({:.3g} N to {:.3g} N, static "
                            "{:.3g} N): the contact solution is not stable at this dt and alpha",
                            wheel_name(layout_.contacts[static_cast<std::size_t>(c)]), P_old[c], P_new[c], Q0_[c]),
                t_new, static_cast<int>(c), std::abs(dP) / q0);
      return {StatusCode::kUnstable,
              fmt::format("contact chatter: the force of wheel {} changes direction every step by more than {:g} of "
                          "its static load",
                          wheel_name(layout_.contacts[static_cast<std::size_t>(c)]), limits_.chatter_fraction)};
    }
    const ContactSpec& cs = layout_.contacts[static_cast<std::size_t>(c)];
    // Tension outside the window (a wheel running off the exit rail end) is
    // no result: the window's envelopes do not contain it.
    if (!cs.law->unilateral() && P_new[c] < 0.0 &&
        window_.contains(TrainLayout::position_m(front_x_m, cs.offset_m))) {
      auto& m = min_tension_ratio_[static_cast<std::size_t>(c)];
      const double ratio = P_new[c] / q0;
      if (m == 0.0 && !std::any_of(warnings_.begin(), warnings_.end(),
                                   [](const RunWarning& w) { return w.code == "tensile_contact"; }))
        warnings_.push_back({"tensile_contact",
                             fmt::format("bilateral contact of wheel {} holds the wheel in tension ({:.3g} N): "
                                         "a unilateral law would lift it; unloading beyond 1 is the model's, "
                                         "not the train's",
                                         wheel_name(cs), P_new[c]),
                             t_new, static_cast<int>(c), std::nullopt});
      m = std::min(m, ratio);
    }
  }
  return Status::Ok();
}

double RunMonitor::energy_residual() const {
  double scale = max_mechanical_change_J_;
  const auto add = [&](const auto& account) {
    const EnergyTotals& e = account.totals();
    scale += e.abs_work_J + e.abs_damping_J + e.abs_hht_J;
  };
  add(structure_energy_);
  for (const auto& a : vehicle_energy_) add(a);
  // A run where nothing moves (a stationary load) has no energy flow: its
  // residual is round-off of the initial energy, not a relative error.
  double initial = std::abs(structure_energy_.initial_mechanical_J());
  for (const auto& a : vehicle_energy_) initial += std::abs(a.initial_mechanical_J());
  scale = std::max({scale, 1e-6 * initial, 1e-9});
  return max_residual_J_ / scale;
}

void RunMonitor::summarize(RunSummary& summary) const {
  summary.energy_residual = energy_checked_ ? energy_residual() : std::numeric_limits<double>::quiet_NaN();
  summary.warnings = warnings_;
  for (RunWarning& w : summary.warnings)
    if (w.code == "tensile_contact" && w.wheel) w.factor = -min_tension_ratio_[static_cast<std::size_t>(*w.wheel)];
  if (energy_checked_ && summary.energy_residual > limits_.energy_warning)
    summary.warnings.push_back(
        {"energy_balance",
         fmt::format("the discrete energy balance (loads and contact work against kinetic, strain, damping and HHT "
                     "energy) closes only to a relative {:.2e}: a step's equations held only approximately",
                     summary.energy_residual),
         std::nullopt, std::nullopt, summary.energy_residual});
  const int high = std::max(10, scene_.analysis.max_newton_iterations / 2);
  if (max_iterations_ > high)
    summary.warnings.push_back({"newton_iterations_high",
                                fmt::format("a step needed {} Newton iterations (more than {}): the contact problem "
                                            "is hard at this dt; check with dt/2",
                                            max_iterations_, high),
                                std::nullopt, std::nullopt, static_cast<double>(max_iterations_)});
}

}  // namespace railvsi
