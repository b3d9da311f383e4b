#pragma once
// Euler-Bernoulli plane beam element, DOFs (v_i, theta_i, v_j, theta_j),
// v upward, theta = dv/dx. Consistent mass.
#include <Eigen/Dense>

namespace railvsi {

using Matrix4 = Eigen::Matrix4d;

inline Matrix4 beam_stiffness(double EI_Nm2, double h_m) {
  const double h = h_m, h2 = h * h;
  Matrix4 k;
  k << 12, 6 * h, -12, 6 * h,  //
      6 * h, 4 * h2, -6 * h, 2 * h2,  //
      -12, -6 * h, 12, -6 * h,  //
      6 * h, 2 * h2, -6 * h, 4 * h2;
  return k * (EI_Nm2 / (h2 * h));
}

inline Matrix4 beam_consistent_mass(double mass_kg_per_m, double h_m) {
  const double h = h_m, h2 = h * h;
  Matrix4 m;
  m << 156, 22 * h, 54, -13 * h,  //
      22 * h, 4 * h2, 13 * h, -3 * h2,  //
      54, 13 * h, 156, -22 * h,  //
      -13 * h, -3 * h2, -22 * h, 4 * h2;
  return m * (mass_kg_per_m * h / 420.0);
}

}  // namespace railvsi
