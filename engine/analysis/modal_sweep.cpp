#include "analysis/modal_sweep.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include <fmt/format.h>

#include "core/input_error.hpp"

namespace railvsi {

ModalSweep::ModalSweep(const ModalBasis& basis, const Train& train, const std::vector<int>& rail_lines, double dt_s,
                       std::shared_ptr<const ModalSectionForces> sections)
    : basis_(basis), n_modes_(basis.num_modes()), dt_s_(dt_s), sections_(std::move(sections)) {
  width_ = n_modes_ + (sections_ ? sections_->num_forms() : 0);
  for (double w : basis.omega_rad_s()) inverse_omega2_.push_back(1.0 / (w * w));
  if (!train.is_moving_forces()) throw InputError("/train", "the modal moving-force rung needs a train of moving forces");
  if (rail_lines.empty()) throw InputError("/analysis/contact/rail_lines", "no rail line to load");
  for (int k = 0; k < n_modes_; ++k)
    steps_.push_back(make_modal_step(basis.omega_rad_s()[static_cast<std::size_t>(k)],
                                     basis.zeta()[static_cast<std::size_t>(k)], dt_s));
  share_ = 1.0 / static_cast<double>(rail_lines.size());
  std::vector<MovingForce> axles = train.moving_forces;
  std::stable_sort(axles.begin(), axles.end(),
                   [](const MovingForce& a, const MovingForce& b) { return a.offset_m < b.offset_m; });
  for (const MovingForce& m : axles) {
    offsets_.push_back(m.offset_m);
    loads_N_.push_back(m.load_N);
  }
  const StructureModel& s = basis.structure();
  const auto n = static_cast<std::size_t>(n_modes_);
  const auto width = static_cast<std::size_t>(width_);
  // The cubic through the values at four interior points of an element
  // (xi = 1/8, 3/8, 5/8, 7/8): exact for the cubic a form's unit value is
  // there, and blind to the node where a shear cut may exclude a load.
  const std::array<double, 4> xi_fit{0.125, 0.375, 0.625, 0.875};
  Eigen::Matrix4d vandermonde;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) vandermonde(i, j) = std::pow(xi_fit[static_cast<std::size_t>(i)], j);
  const Eigen::Matrix4d fit = vandermonde.inverse();
  for (int r : rail_lines) {
    if (r < 0 || r >= static_cast<int>(s.rails().size()))
      throw InputError("/analysis/contact/rail_lines", fmt::format("the structure has no rail line {}", r));
    const RailLine& line = s.rails()[static_cast<std::size_t>(r)];
    Rail rail;
    rail.line = r;
    rail.x_m = line.x_m;
    rail.start_m = line.start_m();
    rail.end_m = line.end_m();
    rail.cubic.assign(line.num_elements() * width * 4, 0.0);
    for (std::size_t e = 0; e < line.num_elements(); ++e) {
      const double h = line.x_m[e + 1] - line.x_m[e];
      for (std::size_t k = 0; k < n; ++k) {
        // End values (v_i, theta_i, v_j, theta_j) of mode k; a fixed DOF is 0.
        double phi[4];
        for (std::size_t j = 0; j < 4; ++j) {
          const int dof = line.element_dofs[e][j];
          phi[j] = dof < 0 ? 0.0 : basis.row(dof)[k];
        }
        // Hermite: N1 = 1 - 3xi^2 + 2xi^3, N2 = h(xi - 2xi^2 + xi^3),
        // N3 = 3xi^2 - 2xi^3, N4 = h(xi^3 - xi^2), collected by powers of xi.
        double* c = rail.cubic.data() + (e * width + k) * 4;
        const double f = -share_;  // downward force, shared between the rails
        c[0] = f * phi[0];
        c[1] = f * h * phi[1];
        c[2] = f * (-3.0 * phi[0] - 2.0 * h * phi[1] + 3.0 * phi[2] - h * phi[3]);
        c[3] = f * (2.0 * phi[0] + h * phi[1] - 2.0 * phi[2] + h * phi[3]);
      }
      for (int form = 0; sections_ && form < sections_->num_forms(); ++form) {
        Eigen::Vector4d values;
        for (int i = 0; i < 4; ++i)
          values[i] = share_ * sections_->statics().unit_form_value(form, r, line.x_m[e] + xi_fit[static_cast<std::size_t>(i)] * h);
        const Eigen::Vector4d coef = fit * values;
        double* c = rail.cubic.data() + (e * width + n + static_cast<std::size_t>(form)) * 4;
        for (int j = 0; j < 4; ++j) c[j] = coef[j];
      }
    }
    rails_.push_back(std::move(rail));
  }
  twist_ = make_deck_twist_gauge(s, rail_lines);
  if (twist_.available()) {
    twist_modes_ = DenseMatrix::Zero(static_cast<Eigen::Index>(twist_.forms.size()), n_modes_);
    for (std::size_t b = 0; b < twist_.forms.size(); ++b)
      for (const auto& [index, coef] : twist_.forms[b]) {
        const double* phi = basis.row(twist_.dofs[static_cast<std::size_t>(index)]);
        for (int k = 0; k < n_modes_; ++k) twist_modes_(static_cast<Eigen::Index>(b), k) += coef * phi[k];
      }
  }
}

void ModalSweep::modal_load(double x, double* p, ModalSweepWorkspace& ws) const {
  const auto n = static_cast<std::size_t>(n_modes_);
  const auto width = static_cast<std::size_t>(width_);
  std::fill_n(p, width, 0.0);
  const std::size_t axles = offsets_.size();
  for (std::size_t r = 0; r < rails_.size(); ++r) {
    const Rail& rail = rails_[r];
    // The axles on the rail have offsets in [x - end, x - start]: the
    // bisection bounds lower_bound(x - end), upper_bound(x - start), moved
    // forward since x only grows.
    std::size_t& first = ws.first[r];
    std::size_t& last = ws.last[r];
    while (first < axles && offsets_[first] < x - rail.end_m) ++first;
    if (last < first) last = first;
    while (last < axles && offsets_[last] <= x - rail.start_m) ++last;
    const std::size_t nodes = rail.x_m.size();
    for (std::size_t a = first; a < last; ++a) {
      const double xa = x - offsets_[a];
      if (!(xa >= rail.start_m && xa <= rail.end_m)) continue;  // as RailLine::covers
      // The element whose nodes bracket xa (the last one at the end), as
      // RailLine::locate finds it by bisection.
      std::size_t& i = ws.element[r * axles + a];
      while (i + 2 < nodes && xa >= rail.x_m[i + 1]) ++i;
      const double xi = (xa - rail.x_m[i]) / (rail.x_m[i + 1] - rail.x_m[i]);
      const double load = loads_N_[a];
      const double* c = rail.cubic.data() + i * width * 4;
      // On a node the forms are evaluated exactly (a shear cut there may
      // exclude the load); inside an element, by their cubics.
      const std::size_t cubic_columns = (sections_ && xi == 0.0) ? n : width;
      for (std::size_t k = 0; k < cubic_columns; ++k, c += 4)
        p[k] += load * (((c[3] * xi + c[2]) * xi + c[1]) * xi + c[0]);
      if (cubic_columns < width) {
        std::fill(ws.form_values.begin(), ws.form_values.end(), 0.0);
        sections_->statics().add_form_values(rail.line, xa, share_ * load, ws.form_values);
        for (std::size_t f = 0; f < ws.form_values.size(); ++f) p[n + f] += ws.form_values[f];
      }
    }
  }
}

ModalSweepRun ModalSweep::run(double x0_m, double speed_mps, long n_steps, ModalSweepWorkspace& ws,
                              bool keep_acceleration, Histories* histories, int history_stride) const {
  const auto n = static_cast<std::size_t>(n_modes_);
  for (auto* v : {&ws.p, &ws.p_next}) v->assign(static_cast<std::size_t>(width_), 0.0);
  for (auto* v : {&ws.q, &ws.qd, &ws.qdd}) v->assign(n, 0.0);
  ws.form_values.assign(sections_ ? static_cast<std::size_t>(sections_->num_forms()) : 0, 0.0);
  ws.element.assign(rails_.size() * offsets_.size(), 0);
  ws.first.assign(rails_.size(), 0);
  ws.last.assign(rails_.size(), 0);
  const StructureModel& s = basis_.structure();
  const DenseMatrix& Phi_out = basis_.at_outputs();
  const std::size_t np = s.outputs().size();
  ModalSweepRun out;
  out.max_abs_displacement_m.assign(np, 0.0);
  out.max_abs_acceleration_mps2.assign(np, 0.0);
  if (sections_) out.sections.emplace(sections_->forms());
  if (twist_.available()) out.max_abs_twist_m = 0.0;
  if (keep_acceleration) {
    ws.acceleration.resize(np);
    for (auto& a : ws.acceleration) a.resize(static_cast<std::size_t>(n_steps) + 1);
  }
  const int stride = std::max(1, history_stride);
  if (histories) {
    Histories& h = *histories;
    h.point_names.clear();
    for (const OutputPoint& o : s.outputs()) h.point_names.push_back(o.name);
    h.deck_displacement_m.assign(np, {});
    h.deck_acceleration_mps2.assign(np, {});
    const auto samples = static_cast<std::size_t>(n_steps / stride + 2);
    h.t_s.reserve(samples);
    for (std::size_t i = 0; i < np; ++i) {
      h.deck_displacement_m[i].reserve(samples);
      h.deck_acceleration_mps2[i].reserve(samples);
    }
  }
  // Deck response at the output points from the modal coordinates; the
  // maxima see every step, the histories every stride.
  const auto record = [&](long step, double t, bool store) {
    if (store) histories->t_s.push_back(t);
    for (std::size_t i = 0; i < np; ++i) {
      const auto row = static_cast<Eigen::Index>(i);
      double u = 0.0, a = 0.0;
      for (std::size_t k = 0; k < n; ++k) {
        u += Phi_out(row, static_cast<Eigen::Index>(k)) * ws.q[k];
        a += Phi_out(row, static_cast<Eigen::Index>(k)) * ws.qdd[k];
      }
      out.max_abs_displacement_m[i] = std::max(out.max_abs_displacement_m[i], std::abs(u));
      out.max_abs_acceleration_mps2[i] = std::max(out.max_abs_acceleration_mps2[i], std::abs(a));
      if (keep_acceleration) ws.acceleration[i][static_cast<std::size_t>(step)] = a;
      if (!store) continue;
      histories->deck_displacement_m[i].push_back(u);
      histories->deck_acceleration_mps2[i].push_back(a);
    }
    for (Eigen::Index b = 0; b < twist_modes_.rows(); ++b) {
      double t = 0.0;
      for (std::size_t k = 0; k < n; ++k) t += twist_modes_(b, static_cast<Eigen::Index>(k)) * ws.q[k];
      if (std::abs(t) > *out.max_abs_twist_m || (step == 0 && b == 0)) {
        out.max_abs_twist_m = std::abs(t);
        out.twist_x_m = twist_.x_m[static_cast<std::size_t>(b)];
      }
    }
  };

  // Start from the static modal response under the loads at t = 0, as the
  // FE rung starts from the static equilibrium.
  modal_load(x0_m, ws.p.data(), ws);
  for (std::size_t k = 0; k < n; ++k) {
    ws.q[k] = ws.p[k] * inverse_omega2_[k];
  }
  record(0, 0.0, histories != nullptr);
  if (sections_) record_sections(ws.p.data(), ws, *out.sections);
  double* q = ws.q.data();
  double* qd = ws.qd.data();
  double* qdd = ws.qdd.data();
  double* p = ws.p.data();
  double* p_next = ws.p_next.data();
  for (long step = 0; step < n_steps; ++step) {
    const double t_new = static_cast<double>(step + 1) * dt_s_;
    modal_load(x0_m + speed_mps * t_new, p_next, ws);
    bool finite = true;
    for (std::size_t k = 0; k < n; ++k) {
      qdd[k] = steps_[k].advance(q[k], qd[k], p[k], p_next[k], dt_s_);
      finite = finite && std::isfinite(q[k]);
    }
    std::swap(p, p_next);
    if (!finite) {
      out.status = {StatusCode::kDiverged, fmt::format("step {}: non-finite modal coordinates", step + 1)};
      break;
    }
    out.steps = step + 1;
    const bool store = histories != nullptr && ((step + 1) % stride == 0 || step + 1 == n_steps);
    record(step + 1, t_new, store);
    if (sections_) record_sections(p, ws, *out.sections);
  }
  return out;
}

void ModalSweep::record_sections(const double* p, ModalSweepWorkspace& ws, SectionEnvelope& envelope) const {
  const auto n = static_cast<std::size_t>(n_modes_);
  // The exact static value under the loads (the sweep's last columns of p)
  // plus the modes' dynamic part.
  for (std::size_t f = 0; f < ws.form_values.size(); ++f) ws.form_values[f] = p[n + f];
  sections_->add_dynamic_part(ws.q.data(), ws.qd.data(), ws.qdd.data(), p, ws.form_values.data());
  envelope.update(ws.form_values);
}

}  // namespace railvsi
