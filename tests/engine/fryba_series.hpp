#pragma once
// Frýba's modal series for a moving constant force on a simply supported
// Euler-Bernoulli beam (L. Frýba, Vibration of Solids and Structures under
// Moving Loads, 1972, §1.3), evaluated in closed form mode by mode: the
// independent reference of the moving-force tests of both rungs.
#include <cmath>
#include <numbers>

namespace railvsi::testing {

inline constexpr double kPi = std::numbers::pi;

// Response at time t of q'' + 2 zeta w q' + w^2 q = F sin(W t), q(0) = q'(0) = 0,
// in closed form (no time stepping).
inline double modal_response(double F, double w, double zeta, double W, double t) {
  if (zeta == 0.0) {
    if (std::abs(w - W) <= 1e-9 * w)  // resonance: limit W -> w of the expression below
      return F / (2.0 * w * w) * (std::sin(w * t) - w * t * std::cos(w * t));
    return F / (w * w - W * W) * (std::sin(W * t) - (W / w) * std::sin(w * t));
  }
  // Steady state A sin(Wt) + B cos(Wt) plus the free response that cancels
  // its initial displacement (B) and velocity (A W).
  const double D = (w * w - W * W) * (w * w - W * W) + (2.0 * zeta * w * W) * (2.0 * zeta * w * W);
  const double A = F * (w * w - W * W) / D;
  const double B = -F * 2.0 * zeta * w * W / D;
  const double steady = A * std::sin(W * t) + B * std::cos(W * t);
  if (zeta < 1.0) {
    const double wd = w * std::sqrt(1.0 - zeta * zeta);
    const double C1 = -B;
    const double C2 = (zeta * w * C1 - A * W) / wd;
    return steady + std::exp(-zeta * w * t) * (C1 * std::cos(wd * t) + C2 * std::sin(wd * t));
  }
  // Overdamped (high modes under stiffness-proportional damping): two real
  // decaying exponentials, written so that nothing overflows.
  const double s = w * std::sqrt(zeta * zeta - 1.0);
  const double r1 = -zeta * w + s, r2 = -zeta * w - s;
  const double D1 = (r2 * B - A * W) / (r1 - r2);
  const double D2 = -B - D1;
  return steady + D1 * std::exp(r1 * t) + D2 * std::exp(r2 * t);
}

struct Beam {
  double L, EI, m;
  double omega(int j) const { return j * j * kPi * kPi / (L * L) * std::sqrt(EI / m); }
};

// Frýba's series for a force P (downward) entering at x = 0 at t = 0, speed v:
// deflection (downward positive) at x, t <= L/v, with modal damping ratios
// zeta(j). With zeta = 0 this is Frýba's closed form (1972, §1.3)
//   w = v0 sum 1/(j^2 (j^2 - a^2)) [sin(j w t) - (a/j) sin(w_j t)] sin(j pi x / L),
// v0 = 2 P L^3 / (pi^4 EI), including the resonant term j = a.
template <class Zeta>
double fryba_deflection(const Beam& b, double P, double v, double x, double t, int modes, Zeta zeta) {
  double w = 0.0;
  for (int j = 1; j <= modes; ++j) {
    const double F = 2.0 * P / (b.m * b.L);  // modal force amplitude per unit modal mass
    const double W = j * kPi * v / b.L;      // forcing frequency of mode j
    w += modal_response(F, b.omega(j), zeta(j), W, t) * std::sin(j * kPi * x / b.L);
  }
  return w;
}

}  // namespace railvsi::testing
