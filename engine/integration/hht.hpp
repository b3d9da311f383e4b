#pragma once
// HHT-alpha time integration (Hilber-Hughes-Taylor), in the form of the
// paper's eq. (3) with Newmark's approximations eqs. (16)-(17):
//   M a'' + (1+alpha) C v - alpha C v_n + (1+alpha) K u - alpha K u_n
//       = (1+alpha) F - alpha F_n,
// alpha in [-1/3, 0]. The functions here are written once for the sparse
// structure and the dense vehicles.
#include <optional>
#include <string>

#include "core/types.hpp"

namespace railvsi {

struct HhtParameters {
  double alpha = -0.05;
  double beta = 0.275625;
  double gamma = 0.55;
  // The consistent pair beta = (1-alpha)^2/4, gamma = (1-2 alpha)/2.
  static HhtParameters from_alpha(double alpha);
};

// Empty when the scheme is unconditionally stable and non-amplifying for
// undamped linear systems; otherwise the reason, for the user.
std::optional<std::string> hht_stability_problem(const HhtParameters& p);

// Spectral radius of the amplification matrix of an undamped oscillator at
// Omega = omega * dt.
double hht_spectral_radius(const HhtParameters& p, double omega_dt);
// Relative period elongation T_bar/T - 1 of an undamped oscillator at
// Omega = omega * dt (from the phase of the principal roots); infinite when
// the roots are real (Omega beyond the scheme's bifurcation).
double hht_period_error(const HhtParameters& p, double omega_dt);

struct HhtCoefficients {
  HhtCoefficients(const HhtParameters& p, double dt_s);
  double alpha, beta, gamma, dt;
  double c0, c1, c2, c3, c4, c5;
  // Effective matrix K_bar = c0 M + (1+alpha) c3 C + (1+alpha) K (eq. 20).
  double mass_factor() const { return c0; }
  double damping_factor() const { return (1.0 + alpha) * c3; }
  double stiffness_factor() const { return 1.0 + alpha; }
};

// Per-subsystem kinematic state.
struct KinematicState {
  Vector u, v, a;
  void resize(Eigen::Index n) {
    u = Vector::Zero(n);
    v = Vector::Zero(n);
    a = Vector::Zero(n);
  }
};

// History part of the right-hand side of K_bar u_{n+1} = rhs + loads:
// everything that depends on the state at t_n only. `work` is scratch.
template <class Mat>
void hht_history_rhs(const HhtCoefficients& h, const Mat& M, const Mat& C, const Mat& K,
                     const KinematicState& s, Vector& rhs, Vector& work) {
  work = h.c0 * s.u + h.c1 * s.v + h.c2 * s.a;
  rhs.noalias() = M * work;
  work = (1.0 + h.alpha) * (h.c3 * s.u - h.c4 * s.v - h.c5 * s.a) + h.alpha * s.v;
  rhs.noalias() += C * work;
  if (h.alpha != 0.0) {
    work = h.alpha * s.u;
    rhs.noalias() += K * work;
  }
}

// Velocities and accelerations at t_{n+1} from the new displacements
// (eqs. 16-17), in place.
void hht_update(const HhtCoefficients& h, const Eigen::Ref<const Vector>& u_new, KinematicState& s);
// The same into `out` (resized), from the state `old` at t_n: the time
// loop swaps its two states instead of copying one. `out` must not share
// storage with `old` or u_new.
void hht_update(const HhtCoefficients& h, const Eigen::Ref<const Vector>& u_new, const KinematicState& old,
                KinematicState& out);

}  // namespace railvsi
