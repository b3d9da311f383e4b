#include "contact/contact_problem.hpp"

#include <cmath>
#include <fmt/format.h>

namespace railvsi {

namespace {

// The generalized Jacobian of Phi at the penetrations delta.
void contact_jacobian(const DenseMatrix& A, const std::vector<const ContactLaw*>& laws, const Vector& delta,
                      DenseMatrix& J) {
  const auto n = delta.size();
  J.setZero(n, n);
  for (Eigen::Index c = 0; c < n; ++c) {
    const ContactLaw& law = *laws[static_cast<std::size_t>(c)];
    if (law.is_constraint()) {
      J.row(c) = A.row(c) / A(c, c);
    } else {
      J.row(c) = law.stiffness(delta[c]) * A.row(c);
      J(c, c) += 1.0;
    }
  }
}

}  // namespace

void contact_residual(const Vector& delta_bar, const DenseMatrix& A,
                      const std::vector<const ContactLaw*>& laws, const Vector& P, Vector& delta,
                      Vector& phi, DenseMatrix* J) {
  const auto n = P.size();
  delta.noalias() = delta_bar - A * P;
  phi.resize(n);
  for (Eigen::Index c = 0; c < n; ++c) {
    const ContactLaw& law = *laws[static_cast<std::size_t>(c)];
    phi[c] = law.is_constraint() ? -delta[c] / A(c, c) : P[c] - law.force(delta[c]);
  }
  if (J) contact_jacobian(A, laws, delta, *J);
}

Status solve_contact_problem(const Vector& delta_bar, const DenseMatrix& A,
                             const std::vector<const ContactLaw*>& laws,
                             const ContactProblemOptions& options, Vector& P,
                             ContactWorkspace& ws, ContactProblemSummary& summary) {
  const double scale = std::max(options.force_scale_N, 1.0);
  summary = {};
  contact_residual(delta_bar, A, laws, P, ws.delta, ws.phi, &ws.J);
  double norm = ws.phi.norm();
  for (int it = 1; it <= options.max_iterations; ++it) {
    summary.iterations = it;
    ws.lu.compute(ws.J);
    ws.dP.noalias() = ws.lu.solve(-ws.phi);
    if (!ws.dP.allFinite())
      return {StatusCode::kDiverged, "contact Newton step is not finite (singular contact Jacobian)"};
    // Backtracking on |Phi|: the Hertz law is stiff and the active set may
    // change within a step.
    double step = 1.0;
    for (int k = 0; k < 8; ++k, step *= 0.5) {
      ws.P_trial = P + step * ws.dP;
      contact_residual(delta_bar, A, laws, ws.P_trial, ws.delta, ws.phi_trial, nullptr);
      if (ws.phi_trial.norm() < norm) break;
    }
    // The last trial is the accepted one: its delta and Phi are at hand,
    // only the Jacobian is new, and needed only if another iteration follows.
    P = ws.P_trial;
    ws.phi.swap(ws.phi_trial);
    norm = ws.phi.norm();
    summary.relative_residual = norm / scale;
    if (!std::isfinite(norm)) return {StatusCode::kDiverged, "contact residual is not finite"};
    if (summary.relative_residual > options.tolerance) {
      contact_jacobian(A, laws, ws.delta, ws.J);
    } else {
      // Make the returned forces admissible: exactly the law's value.
      for (Eigen::Index c = 0; c < P.size(); ++c) {
        const ContactLaw& law = *laws[static_cast<std::size_t>(c)];
        if (!law.is_constraint()) P[c] = law.force(ws.delta[c]);
      }
      return Status::Ok();
    }
  }
  return {StatusCode::kNoConvergence,
          fmt::format("contact Newton did not converge in {} iterations (relative residual {:.3e} > "
                      "{:.1e})",
                      options.max_iterations, summary.relative_residual, options.tolerance)};
}

}  // namespace railvsi
