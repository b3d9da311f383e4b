#include "simulation/energy_balance.hpp"

#include <cmath>

namespace railvsi {

template <class Mat>
EnergyAccount<Mat>::EnergyAccount(const Mat& M, const Mat& C, const Mat& K, const KinematicState& s0,
                                  const Vector& f0)
    : M_(&M), C_(&C), K_(&K) {
  Ku_ = K * s0.u;
  Ku_prev_ = Ku_;
  Cv_ = C * s0.v;
  Cv_prev_ = Cv_;
  Ma_ = M * s0.a;
  fa_ = f0;
  work_ = M * s0.v;
  e_.kinetic_J = 0.5 * s0.v.dot(work_);
  e_.strain_J = 0.5 * s0.u.dot(Ku_);
  e0_ = e_.kinetic_J + e_.strain_J;
}

template <class Mat>
void EnergyAccount<Mat>::step(const HhtCoefficients& h, const KinematicState& old, const KinematicState& now,
                              const Vector& f_alpha) {
  StateProducts p;
  p.Ku = (*K_) * now.u;
  p.Cv = (*C_) * now.v;
  p.Mv = (*M_) * now.v;
  p.Ma = (*M_) * now.a;
  step(h, old, now, f_alpha, p);
}

template <class Mat>
void EnergyAccount<Mat>::step(const HhtCoefficients& h, const KinematicState& old, const KinematicState& now,
                              const Vector& f_alpha, StateProducts& p) {
  const double a = h.alpha;
  du_ = now.u - old.u;
  const Vector& du = du_;
  // Loads: Du' <f^a>.
  const double w = 0.5 * du.dot(f_alpha + fa_);
  // Damping: Du' C <v^a>, v^a_{n+1} = (1+a) v_{n+1} - a v_n, v^a_n = (1+a) v_n - a v_{n-1}.
  const Vector& Cv_new = p.Cv;
  const double d = 0.5 * du.dot((1.0 + a) * Cv_new + Cv_ - a * Cv_prev_);
  // Kinetic and strain energy from the states.
  const Vector& Ku_new = p.Ku;
  const double T = 0.5 * now.v.dot(p.Mv);
  const double U = 0.5 * now.u.dot(Ku_new);
  // HHT term.
  const Vector& Ma_new = p.Ma;
  const double e_hht = -h.dt * (h.gamma - 0.5) * 0.5 * (now.v + old.v).dot(Ma_new - Ma_) +
                       0.5 * h.dt * h.dt * (h.beta - 0.5 * h.gamma) * (now.a.dot(Ma_new) - old.a.dot(Ma_)) +
                       0.5 * a * du.dot(Ku_new - Ku_prev_);
  e_.kinetic_J = T;
  e_.strain_J = U;
  e_.work_J += w;
  e_.damping_J += d;
  e_.hht_J += e_hht;
  e_.abs_work_J += std::abs(w);
  e_.abs_damping_J += std::abs(d);
  e_.abs_hht_J += std::abs(e_hht);
  Ku_prev_.swap(Ku_);
  Ku_.swap(p.Ku);
  Cv_prev_.swap(Cv_);
  Cv_.swap(p.Cv);
  Ma_.swap(p.Ma);
  fa_ = f_alpha;
}

template class EnergyAccount<SparseMatrix>;
template class EnergyAccount<DenseMatrix>;

}  // namespace railvsi
