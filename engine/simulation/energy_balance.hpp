#pragma once
// The discrete energy balance of the HHT-alpha scheme for one linear
// subsystem (the structure, or one vehicle), with every force that is not
// in its own K, C (moving loads, gravity, contact forces) counted as
// external.
//
// Derivation. HHT writes equilibrium with alpha-shifted quantities
// x^a_{n+1} = (1+alpha) x_{n+1} - alpha x_n for u, v and the load f:
//     M a_{n+1} + C v^a_{n+1} + K u^a_{n+1} = f^a_{n+1}.
// Average the equations of steps n and n+1 and multiply by
// Du = u_{n+1} - u_n. With <x> = (x_n + x_{n+1})/2, [[x]] = x_{n+1} - x_n
// and Newmark's relations Du = dt <v> + dt^2 (beta - gamma/2) [[a]],
// [[v]] = dt <a> + dt (gamma - 1/2) [[a]]:
//     Du' M <a>   = DT - dt (gamma - 1/2) <v>' M [[a]]
//                      + dt^2/2 (beta - gamma/2) (a_{n+1}' M a_{n+1} - a_n' M a_n)
//     Du' K <u^a> = DU + alpha/2 Du' K (u_{n+1} - u_{n-1})
// (K, M symmetric; T = v'Mv/2, U = u'Ku/2), so that exactly
//     DT + DU + Du' C <v^a> + E_hht = Du' <f^a>
// with the HHT term
//     E_hht = -dt (gamma - 1/2) <v>' M [[a]] + dt^2/2 (beta - gamma/2) [[a' M a]]
//             + alpha/2 Du' K (u_{n+1} - u_{n-1}).
// For alpha = 0 (beta = 1/4, gamma = 1/2) E_hht vanishes: the trapezoidal
// rule conserves T + U up to the work of damping and loads. For alpha < 0,
// gamma - 1/2 = -alpha and beta - gamma/2 = alpha^2/4.
// The balance is checked with T and U computed from the states, so a
// residual measures equations that did not hold (an unchecked solve, a
// contact force applied inconsistently to rail and wheel, an unconverged
// step), not an identity.
//
// The state before the first step is an equilibrium (static), whose
// "previous step" is itself: u_{-1} = u_0, f^a_0 = f_0.
#include "integration/history_operator.hpp"
#include "integration/hht.hpp"

namespace railvsi {

struct EnergyTotals {
  double kinetic_J = 0.0;
  double strain_J = 0.0;
  double damping_J = 0.0;    // dissipated by C, accumulated
  double hht_J = 0.0;        // E_hht, accumulated
  double work_J = 0.0;       // of the loads, accumulated
  double abs_work_J = 0.0;   // sum of |work| per step (a scale)
  double abs_damping_J = 0.0;
  double abs_hht_J = 0.0;
};

template <class Mat>
class EnergyAccount {
 public:
  EnergyAccount() = default;
  EnergyAccount(const Mat& M, const Mat& C, const Mat& K, const KinematicState& s0, const Vector& f0);

  // After a step from `old` (t_n) to `now` (t_{n+1}) with the shifted load
  // f^a_{n+1} = (1+alpha) f_{n+1} - alpha f_n.
  void step(const HhtCoefficients& h, const KinematicState& old, const KinematicState& now, const Vector& f_alpha);
  // The same with the products K u, C v, M v, M a of `now` given (computed
  // in the pass that forms the next step's history terms).
  // Their vectors are swapped into the account (left with others of the
  // same size, for the next pass to overwrite).
  void step(const HhtCoefficients& h, const KinematicState& old, const KinematicState& now, const Vector& f_alpha,
            StateProducts& now_products);
  // The same with the loads f_{n+1}, f_n given: f^a_{n+1} is formed in the
  // one pass over the rows that takes every dot product of the step.
  void step(const HhtCoefficients& h, const KinematicState& old, const KinematicState& now, const Vector& f_new,
            const Vector& f_old, StateProducts& now_products);

  const EnergyTotals& totals() const { return e_; }
  double initial_mechanical_J() const { return e0_; }

 private:
  const Mat* M_ = nullptr;
  const Mat* C_ = nullptr;
  const Mat* K_ = nullptr;
  Vector Ku_prev_, Ku_;       // K u_{n-1}, K u_n
  Vector Cv_prev_, Cv_;       // C v_{n-1}, C v_n
  Vector Ma_;                 // M a_n
  Vector fa_;                 // f^a_n
  StateProducts scratch_;     // the products of `now` when the caller has none
  // One pass over the rows: the step's dot products; fa_ becomes f^a_{n+1}
  // (load_at(i): its entry i).
  template <class LoadAt>
  void accumulate(const HhtCoefficients& h, const KinematicState& old, const KinematicState& now, LoadAt load_at,
                  StateProducts& p);
  EnergyTotals e_;
  double e0_ = 0.0;
};

}  // namespace railvsi
