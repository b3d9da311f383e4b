#pragma once
// Rayleigh damping C = a0 M + a1 K with the ratio zeta matched at two
// frequencies: zeta(w) = a0/(2w) + a1 w/2 equals zeta at w1 and w2.
#include <numbers>

namespace railvsi {

struct RayleighCoefficients {
  double a0_per_s = 0.0;
  double a1_s = 0.0;
};

inline RayleighCoefficients rayleigh_coefficients(double ratio, double f1_hz, double f2_hz) {
  const double w1 = 2.0 * std::numbers::pi * f1_hz, w2 = 2.0 * std::numbers::pi * f2_hz;
  return {2.0 * ratio * w1 * w2 / (w1 + w2), 2.0 * ratio / (w1 + w2)};
}

}  // namespace railvsi
