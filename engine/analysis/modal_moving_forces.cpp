#include "analysis/modal_moving_forces.hpp"

#include <chrono>
#include <cmath>

#include <fmt/format.h>

#include "analysis/modal_analysis.hpp"
#include "core/input_error.hpp"
#include "integration/modal_recurrence.hpp"
#include "simulation/simulation.hpp"
#include "simulation/static_equilibrium.hpp"

namespace railvsi {
namespace {

using Clock = std::chrono::steady_clock;

// The lowest modes, enough of them to pass max_frequency_hz: asked in
// growing batches until the highest one computed lies above it (or the
// model has no more).
ModalResult modes_up_to(const StructureModel& s, const ModalMovingForceOptions& o) {
  int asked = std::max(8, o.min_modes);
  for (;;) {
    ModalOptions mo;
    mo.modes = std::min(asked, s.num_dofs() - 1);
    ModalResult r = modal_analysis(s, mo);
    if (!r.status.ok()) throw InputError("/structure", "modal analysis: " + r.status.message());
    const bool enough = r.frequencies_hz.empty() || r.frequencies_hz.back() > o.max_frequency_hz;
    if (enough || mo.modes >= s.num_dofs() - 1) {
      int keep = 0;
      while (keep < static_cast<int>(r.frequencies_hz.size()) &&
             (r.frequencies_hz[static_cast<std::size_t>(keep)] <= o.max_frequency_hz || keep < o.min_modes))
        ++keep;
      r.frequencies_hz.resize(static_cast<std::size_t>(keep));
      r.shapes = r.shapes.leftCols(keep).eval();
      return r;
    }
    asked *= 2;
  }
}

}  // namespace

Result run_modal_moving_forces(const Scene& scene, const ModalMovingForceOptions& options) {
  const auto t_start = Clock::now();
  if (!scene.train.is_moving_forces())
    throw InputError("/train", "the modal moving-force rung needs a train of moving forces");
  if (!(options.max_frequency_hz > 0.0)) throw InputError("", "modal cut-off frequency must be > 0");
  const StructureModel& s = *scene.structure;
  const AnalysisOptions& an = scene.analysis;
  const double dt = an.dt_s;
  const double x0 = scene.start_x_m.value_or(default_start_x_m(scene));
  const double duration = an.duration_s.value_or(default_duration_s(scene, x0));
  if (!(duration > 0.0) || !std::isfinite(duration))
    throw InputError("/analysis/duration_s", "the run has no duration: give speed_kmh > 0 or analysis.duration_s");

  const ModalResult modes = modes_up_to(s, options);
  const auto n_modes = static_cast<Eigen::Index>(modes.frequencies_hz.size());
  const DenseMatrix& Phi = modes.shapes;  // mass-normalised columns
  std::vector<ModalStep> steps;
  std::vector<double> omega(static_cast<std::size_t>(n_modes)), zeta(static_cast<std::size_t>(n_modes));
  for (Eigen::Index k = 0; k < n_modes; ++k) {
    const double w = 2.0 * M_PI * modes.frequencies_hz[static_cast<std::size_t>(k)];
    const Vector phi = Phi.col(k);
    // The diagonal of Phi^T C Phi: exact for Rayleigh damping, the modal
    // approximation otherwise (the coupling terms are left out).
    const double z = phi.dot(s.C() * phi) / (2.0 * w);
    omega[static_cast<std::size_t>(k)] = w;
    zeta[static_cast<std::size_t>(k)] = z;
    steps.push_back(make_modal_step(w, z, dt));
  }

  // Modal load of the moving forces with the first axle at x: p = Phi^T f.
  Vector f = Vector::Zero(s.num_dofs());
  const auto modal_load = [&](double x, Vector& p) {
    f.setZero();
    add_moving_force_loads(scene, x, f);
    p.noalias() = Phi.transpose() * f;
  };
  DenseMatrix Phi_out(static_cast<Eigen::Index>(s.outputs().size()), n_modes);
  for (std::size_t i = 0; i < s.outputs().size(); ++i) Phi_out.row(static_cast<Eigen::Index>(i)) = Phi.row(s.outputs()[i].dof);

  Result result;
  RunSummary& sum = result.summary;
  sum.dt_s = dt;
  sum.fidelity.model = "moving-forces";
  sum.fidelity.contact_law = "none";
  sum.fidelity.solver_path = "modal-exact";
  sum.fidelity.structure_backend =
      fmt::format("modal ({} modes up to {:.4g} Hz, exact recurrence)", n_modes, options.max_frequency_hz);
  sum.fidelity.structure_dofs = s.num_dofs();

  // Start from the static modal response under the loads at t = 0, as the
  // FE rung starts from the static equilibrium.
  Vector p(n_modes), p_next(n_modes), q(n_modes), qd = Vector::Zero(n_modes), qdd(n_modes);
  modal_load(x0, p);
  for (Eigen::Index k = 0; k < n_modes; ++k) q[k] = p[k] / (omega[static_cast<std::size_t>(k)] * omega[static_cast<std::size_t>(k)]);
  qdd.setZero();

  Histories& h = result.histories;
  const std::size_t np = s.outputs().size();
  for (const OutputPoint& o : s.outputs()) h.point_names.push_back(o.name);
  h.deck_displacement_m.resize(np);
  h.deck_acceleration_mps2.resize(np);
  std::vector<double> max_u(np, 0.0), max_a(np, 0.0);
  Vector u_out(static_cast<Eigen::Index>(np)), a_out(static_cast<Eigen::Index>(np));
  const auto record = [&](double t, bool store) {
    u_out.noalias() = Phi_out * q;
    a_out.noalias() = Phi_out * qdd;
    for (std::size_t i = 0; i < np; ++i) {
      max_u[i] = std::max(max_u[i], std::abs(u_out[static_cast<Eigen::Index>(i)]));
      max_a[i] = std::max(max_a[i], std::abs(a_out[static_cast<Eigen::Index>(i)]));
    }
    if (!store) return;
    h.t_s.push_back(t);
    for (std::size_t i = 0; i < np; ++i) {
      h.deck_displacement_m[i].push_back(u_out[static_cast<Eigen::Index>(i)]);
      h.deck_acceleration_mps2[i].push_back(a_out[static_cast<Eigen::Index>(i)]);
    }
  };
  sum.setup_s = std::chrono::duration<double>(Clock::now() - t_start).count();
  const long n_steps = static_cast<long>(std::ceil(duration / dt - 1e-9));
  record(0.0, true);
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
  }
  for (std::size_t i = 0; i < np; ++i) {
    sum.points.push_back({s.outputs()[i].name, s.outputs()[i].x_m, max_u[i], max_a[i]});
    sum.max_abs_displacement_m = std::max(sum.max_abs_displacement_m, max_u[i]);
    sum.max_abs_acceleration_mps2 = std::max(sum.max_abs_acceleration_mps2, max_a[i]);
  }
  sum.wall_s = std::chrono::duration<double>(Clock::now() - t_start).count();
  return result;
}

}  // namespace railvsi
