#include "integration/hht.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <fmt/format.h>

namespace railvsi {

HhtParameters HhtParameters::from_alpha(double alpha) {
  return {alpha, 0.25 * (1.0 - alpha) * (1.0 - alpha), 0.5 * (1.0 - 2.0 * alpha)};
}

HhtCoefficients::HhtCoefficients(const HhtParameters& p, double dt_s)
    : alpha(p.alpha), beta(p.beta), gamma(p.gamma), dt(dt_s) {
  c0 = 1.0 / (beta * dt * dt);
  c1 = 1.0 / (beta * dt);
  c2 = 1.0 / (2.0 * beta) - 1.0;
  c3 = gamma / (beta * dt);
  c4 = 1.0 - gamma / beta;
  c5 = dt * (1.0 - gamma / (2.0 * beta));
}

void hht_update(const HhtCoefficients& h, const Eigen::Ref<const Vector>& u_new, KinematicState& s) {
  // The coefficients in locals: the stores could alias h, which the
  // compiler would otherwise reload at every entry.
  const double c0 = h.c0, c1 = h.c1, c2 = h.c2, dt = h.dt, gamma = h.gamma, one_gamma = 1.0 - h.gamma;
  for (Eigen::Index i = 0; i < u_new.size(); ++i) {
    const double a_new = c0 * (u_new[i] - s.u[i]) - c1 * s.v[i] - c2 * s.a[i];
    s.v[i] += dt * (one_gamma * s.a[i] + gamma * a_new);
    s.a[i] = a_new;
    s.u[i] = u_new[i];
  }
}

void hht_update(const HhtCoefficients& h, const Eigen::Ref<const Vector>& u_new, const KinematicState& old,
                KinematicState& out) {
  const Eigen::Index n = u_new.size();
  out.u.resize(n);
  out.v.resize(n);
  out.a.resize(n);
  const double c0 = h.c0, c1 = h.c1, c2 = h.c2, dt = h.dt, gamma = h.gamma, one_gamma = 1.0 - h.gamma;
  const double* un = u_new.data();
  const double* ou = old.u.data();
  const double* ov = old.v.data();
  const double* oa = old.a.data();
  double* __restrict nu = out.u.data();
  double* __restrict nv = out.v.data();
  double* __restrict na = out.a.data();
  for (Eigen::Index i = 0; i < n; ++i) {
    const double a_new = c0 * (un[i] - ou[i]) - c1 * ov[i] - c2 * oa[i];
    nv[i] = ov[i] + dt * (one_gamma * oa[i] + gamma * a_new);
    na[i] = a_new;
    nu[i] = un[i];
  }
}

namespace {

// One step of m=1, k=Omega^2, c=0, dt=1 applied to the unit states.
Eigen::Matrix3d amplification_matrix(const HhtParameters& p, double omega_dt) {
  const HhtCoefficients h(p, 1.0);
  const double k = omega_dt * omega_dt;
  const double kbar = h.c0 + (1.0 + h.alpha) * k;
  Eigen::Matrix3d A;
  for (int j = 0; j < 3; ++j) {
    KinematicState s;
    s.u = Vector::Zero(1);
    s.v = Vector::Zero(1);
    s.a = Vector::Zero(1);
    (j == 0 ? s.u : j == 1 ? s.v : s.a)[0] = 1.0;
    const double rhs = h.c0 * s.u[0] + h.c1 * s.v[0] + h.c2 * s.a[0] + h.alpha * k * s.u[0];
    Vector u_new(1);
    u_new[0] = rhs / kbar;
    hht_update(h, u_new, s);
    A.col(j) << s.u[0], s.v[0], s.a[0];
  }
  return A;
}

}  // namespace

double hht_spectral_radius(const HhtParameters& p, double omega_dt) {
  return amplification_matrix(p, omega_dt).eigenvalues().cwiseAbs().maxCoeff();
}

double hht_period_error(const HhtParameters& p, double omega_dt) {
  // The principal roots are the complex pair rho exp(+-i Omega_bar); the
  // numerical period is 2 pi / Omega_bar. The spurious root is real (for
  // alpha < 0 it may be negative: its phase pi is not a period).
  const Eigen::Vector3cd lambda = amplification_matrix(p, omega_dt).eigenvalues();
  double omega_bar = 0.0;
  for (const auto& l : lambda)
    if (std::abs(l.imag()) > 1e-12 * std::abs(l)) omega_bar = std::max(omega_bar, std::abs(std::arg(l)));
  return omega_bar > 0.0 ? omega_dt / omega_bar - 1.0 : std::numeric_limits<double>::infinity();
}

std::optional<std::string> hht_stability_problem(const HhtParameters& p) {
  if (!(p.alpha >= -1.0 / 3.0 - 1e-15 && p.alpha <= 0.0))
    return fmt::format("hht_alpha = {} is outside [-1/3, 0]", p.alpha);
  if (!(p.beta > 0.0)) return fmt::format("hht_beta = {} must be > 0", p.beta);
  if (!(p.gamma >= 0.5 - 1e-12))  // NaN too
    return fmt::format("hht_gamma = {} < 1/2: the scheme has negative numerical damping and "
                       "amplifies the response (use gamma = (1-2 alpha)/2 = {})",
                       p.gamma, 0.5 * (1.0 - 2.0 * p.alpha));
  // The consistent pair with alpha in [-1/3, 0] is unconditionally stable
  // (Hilber, Hughes & Taylor 1977, Earthquake Engng Struct. Dyn. 5, 283-292):
  // no scan. Every scene that leaves beta and gamma out has it, and a sweep
  // parses thousands of scenes.
  const HhtParameters consistent = HhtParameters::from_alpha(p.alpha);
  if (p.beta == consistent.beta && p.gamma == consistent.gamma) return std::nullopt;
  // Otherwise, scan the amplification matrix over the whole frequency range.
  for (double lg = -3.0; lg <= 7.0; lg += 0.05) {
    const double omega_dt = std::pow(10.0, lg);
    const double rho = hht_spectral_radius(p, omega_dt);
    if (rho > 1.0 + 1e-9)
      return fmt::format("hht_beta = {}, hht_gamma = {} with alpha = {} amplify the response "
                         "(spectral radius {:.6f} > 1 at omega*dt = {:.3g}); the consistent "
                         "values are beta = (1-alpha)^2/4 = {}, gamma = (1-2 alpha)/2 = {}",
                         p.beta, p.gamma, p.alpha, rho, omega_dt,
                         0.25 * (1.0 - p.alpha) * (1.0 - p.alpha), 0.5 * (1.0 - 2.0 * p.alpha));
  }
  return std::nullopt;
}

}  // namespace railvsi
