#include "analysis/modal_moving_forces.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

#include <fmt/format.h>

#include "core/input_error.hpp"
#include "integration/modal_recurrence.hpp"
#include "simulation/simulation.hpp"
#include "simulation/static_equilibrium.hpp"

namespace railvsi {
namespace {

using Clock = std::chrono::steady_clock;

}  // namespace

Result run_modal_moving_forces(const Scene& scene, const ModalBasis& basis) {
  const auto t_start = Clock::now();
  if (!scene.train.is_moving_forces())
    throw InputError("/train", "the modal moving-force rung needs a train of moving forces");
  if (&basis.structure() != scene.structure.get())
    throw InputError("/structure", "the modal basis was computed for another structure");
  const StructureModel& s = *scene.structure;
  const AnalysisOptions& an = scene.analysis;
  const double dt = an.dt_s;
  const double x0 = scene.start_x_m.value_or(default_start_x_m(scene));
  const double duration = an.duration_s.value_or(default_duration_s(scene, x0));
  if (!(duration > 0.0) || !std::isfinite(duration))
    throw InputError("/analysis/duration_s", "the run has no duration: give speed_kmh > 0 or analysis.duration_s");

  const Eigen::Index n_modes = basis.num_modes();
  std::vector<ModalStep> steps;
  for (Eigen::Index k = 0; k < n_modes; ++k)
    steps.push_back(make_modal_step(basis.omega_rad_s()[static_cast<std::size_t>(k)],
                                    basis.zeta()[static_cast<std::size_t>(k)], dt));

  // Modal load of the moving forces with the first axle at x: p = Phi^T f,
  // summed over the few rail DOFs under the axles (downward loads, shared
  // equally between the rail lines the train bears on).
  const auto& rails = an.contact.rail_lines;
  const double share = 1.0 / static_cast<double>(rails.size());
  // Axles by offset: those on a rail line at x have offsets in
  // [x - rail end, x - rail start], a contiguous range found by bisection,
  // so a step costs the axles on the structure, not the whole train.
  std::vector<MovingForce> axles = scene.train.moving_forces;
  std::stable_sort(axles.begin(), axles.end(),
                   [](const MovingForce& a, const MovingForce& b) { return a.offset_m < b.offset_m; });
  std::vector<double> offsets;
  for (const MovingForce& m : axles) offsets.push_back(m.offset_m);
  const auto on_rail = [&](const RailLine& rail, double x) {
    const auto first = std::lower_bound(offsets.begin(), offsets.end(), x - rail.end_m());
    const auto last = std::upper_bound(offsets.begin(), offsets.end(), x - rail.start_m());
    return std::pair{static_cast<std::size_t>(first - offsets.begin()), static_cast<std::size_t>(last - offsets.begin())};
  };
  const auto modal_load = [&](double x, Vector& p) {
    p.setZero();
    for (int r : rails) {
      const RailLine& rail = s.rails()[static_cast<std::size_t>(r)];
      const auto [first, last] = on_rail(rail, x);
      for (std::size_t i = first; i < last; ++i) {
        const MovingForce& m = axles[i];
        const auto row = rail.locate(x - m.offset_m);
        if (!row) continue;
        for (int j = 0; j < 4; ++j) {
          if (row->dof[j] < 0) continue;
          const double f = -share * row->weight[j] * m.load_N;
          const double* phi = basis.row(row->dof[j]);
          for (Eigen::Index k = 0; k < n_modes; ++k) p[k] += f * phi[k];
        }
      }
    }
  };
  const DenseMatrix& Phi_out = basis.at_outputs();

  Result result;
  RunSummary& sum = result.summary;
  sum.dt_s = dt;
  sum.fidelity.model = "moving-forces";
  sum.fidelity.contact_law = "none";
  sum.fidelity.solver_path = "modal-exact";
  sum.fidelity.structure_backend =
      fmt::format("modal ({} modes up to {:.4g} Hz, exact recurrence)", n_modes, basis.max_frequency_hz());
  sum.fidelity.structure_dofs = s.num_dofs();

  // Start from the static modal response under the loads at t = 0, as the
  // FE rung starts from the static equilibrium.
  Vector p(n_modes), p_next(n_modes), q(n_modes), qd = Vector::Zero(n_modes), qdd(n_modes);
  modal_load(x0, p);
  for (Eigen::Index k = 0; k < n_modes; ++k) {
    const double w = basis.omega_rad_s()[static_cast<std::size_t>(k)];
    q[k] = p[k] / (w * w);
  }
  qdd.setZero();

  // Section forces by the mode-acceleration method: the exact static value
  // under the loads at t (influence lines) plus the modes' dynamic part
  // (q - p/omega^2 on u, q' on v, q'' on a). Modal superposition of u alone
  // would miss the higher modes' static share: about 10 % of the midspan
  // moment of a point load with three modes kept.
  const StaticInfluence* statics = basis.statics();
  const std::optional<SectionForms> no_forms =
      statics ? std::nullopt : std::optional<SectionForms>(make_section_forms(s));
  const SectionForms& forms = statics ? statics->section_forms() : *no_forms;
  SectionEnvelope section_envelope(forms);
  std::vector<double> form_values(forms.forms.size());
  Vector q_dyn(n_modes);
  const auto record_sections = [&](double x, const Vector& p_now) {
    std::fill(form_values.begin(), form_values.end(), 0.0);
    for (int r : rails) {
      const auto [first, last] = on_rail(s.rails()[static_cast<std::size_t>(r)], x);
      for (std::size_t i = first; i < last; ++i)
        statics->add_form_values(r, x - axles[i].offset_m, share * axles[i].load_N, form_values);
    }
    for (Eigen::Index k = 0; k < n_modes; ++k) {
      const double w = basis.omega_rad_s()[static_cast<std::size_t>(k)];
      q_dyn[k] = q[k] - p_now[k] / (w * w);
    }
    for (std::size_t f = 0; f < form_values.size(); ++f) {
      const auto row = static_cast<Eigen::Index>(f);
      form_values[f] += basis.forms_on_u().row(row).dot(q_dyn) + basis.forms_on_v().row(row).dot(qd) +
                        basis.forms_on_a().row(row).dot(qdd);
    }
    section_envelope.update(form_values);
  };

  Histories& h = result.histories;
  const std::size_t np = s.outputs().size();
  for (const OutputPoint& o : s.outputs()) h.point_names.push_back(o.name);
  h.deck_displacement_m.resize(np);
  h.deck_acceleration_mps2.resize(np);
  std::vector<double> max_u(np, 0.0), max_a(np, 0.0);
  // Deck response at the output points from the modal coordinates; the
  // maxima see every step, the histories every stride.
  const auto record = [&](double t, bool store) {
    if (store) h.t_s.push_back(t);
    for (std::size_t i = 0; i < np; ++i) {
      const auto row = static_cast<Eigen::Index>(i);
      double u = 0.0, a = 0.0;
      for (Eigen::Index k = 0; k < n_modes; ++k) {
        u += Phi_out(row, k) * q[k];
        a += Phi_out(row, k) * qdd[k];
      }
      max_u[i] = std::max(max_u[i], std::abs(u));
      max_a[i] = std::max(max_a[i], std::abs(a));
      if (!store) continue;
      h.deck_displacement_m[i].push_back(u);
      h.deck_acceleration_mps2[i].push_back(a);
    }
  };
  const long n_steps = static_cast<long>(std::ceil(duration / dt - 1e-9));
  const auto samples = static_cast<std::size_t>(n_steps / std::max(1, an.history_stride) + 2);
  h.t_s.reserve(samples);
  for (std::size_t i = 0; i < np; ++i) {
    h.deck_displacement_m[i].reserve(samples);
    h.deck_acceleration_mps2[i].reserve(samples);
  }
  sum.setup_s = std::chrono::duration<double>(Clock::now() - t_start).count();
  record(0.0, true);
  if (statics) record_sections(x0, p);
  for (long n = 0; n < n_steps; ++n) {
    const double t_new = static_cast<double>(n + 1) * dt;
    modal_load(x0 + scene.speed_mps * t_new, p_next);
    for (Eigen::Index k = 0; k < n_modes; ++k)
      qdd[k] = steps[static_cast<std::size_t>(k)].advance(q[k], qd[k], p[k], p_next[k], dt);
    std::swap(p, p_next);
    if (!q.allFinite()) {
      result.status = {StatusCode::kDiverged, fmt::format("step {}: non-finite modal coordinates", n + 1)};
      break;
    }
    sum.steps = n + 1;
    const bool store = ((n + 1) % std::max(1, an.history_stride) == 0) || n + 1 == n_steps;
    record(t_new, store);
    if (statics) record_sections(x0 + scene.speed_mps * t_new, p);
  }
  for (std::size_t i = 0; i < np; ++i) {
    sum.points.push_back({s.outputs()[i].name, s.outputs()[i].x_m, max_u[i], max_a[i], std::nullopt, std::nullopt});
    sum.max_abs_displacement_m = std::max(sum.max_abs_displacement_m, max_u[i]);
    sum.max_abs_acceleration_mps2 = std::max(sum.max_abs_acceleration_mps2, max_a[i]);
  }
  section_envelope.summarize(sum);
  sum.wall_s = std::chrono::duration<double>(Clock::now() - t_start).count();
  return result;
}

Result run_modal_moving_forces(const Scene& scene, const ModalMovingForceOptions& options) {
  const auto t_start = Clock::now();
  const ModalBasis basis(scene.structure, options);
  const double modes_s = std::chrono::duration<double>(Clock::now() - t_start).count();
  Result r = run_modal_moving_forces(scene, basis);
  r.summary.setup_s += modes_s;
  r.summary.wall_s += modes_s;
  return r;
}

}  // namespace railvsi
