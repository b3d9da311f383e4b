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
  const Vector Mv = M * s0.v;
  e_.kinetic_J = 0.5 * s0.v.dot(Mv);
  e_.strain_J = 0.5 * s0.u.dot(Ku_);
  e0_ = e_.kinetic_J + e_.strain_J;
}

template <class Mat>
void EnergyAccount<Mat>::step(const HhtCoefficients& h, const KinematicState& old, const KinematicState& now,
                              const Vector& f_alpha) {
  scratch_.Ku.noalias() = (*K_) * now.u;
  scratch_.Cv.noalias() = (*C_) * now.v;
  scratch_.Mv.noalias() = (*M_) * now.v;
  scratch_.Ma.noalias() = (*M_) * now.a;
  step(h, old, now, f_alpha, scratch_);
}

template <class Mat>
void EnergyAccount<Mat>::step(const HhtCoefficients& h, const KinematicState& old, const KinematicState& now,
                              const Vector& f_alpha, StateProducts& p) {
  const double* f = f_alpha.data();
  accumulate(h, old, now, [f](Eigen::Index i) { return f[i]; }, p);
}

template <class Mat>
void EnergyAccount<Mat>::step(const HhtCoefficients& h, const KinematicState& old, const KinematicState& now,
                              const Vector& f_new, const Vector& f_old, StateProducts& p) {
  const double* fn = f_new.data();
  const double* fo = f_old.data();
  const double one_a = 1.0 + h.alpha, a = h.alpha;
  accumulate(h, old, now, [=](Eigen::Index i) { return one_a * fn[i] - a * fo[i]; }, p);
}

// The sums of the energy balance in one pass over the rows (they were
// eleven passes of Eigen's, and two temporaries), two rows per SSE2 pair:
// they only enter the run monitor's energy residual, a rounding-level check
// whose own rounding this changes.
template <class Mat>
template <class LoadAt>
void EnergyAccount<Mat>::accumulate(const HhtCoefficients& h, const KinematicState& old, const KinematicState& now,
                                    LoadAt load_at, StateProducts& p) {
  using Two = double __attribute__((vector_size(2 * sizeof(double))));
  const double a = h.alpha;
  const Eigen::Index n = now.u.size();
  fa_.resize(n);  // the same size after the first step
  const double *un = now.u.data(), *vn = now.v.data(), *an = now.a.data();
  const double *uo = old.u.data(), *vo = old.v.data(), *ao = old.a.data();
  const double *ku = p.Ku.data(), *cv = p.Cv.data(), *mv = p.Mv.data(), *ma = p.Ma.data();
  const double *ku_prev = Ku_prev_.data(), *cv_n = Cv_.data(), *cv_prev = Cv_prev_.data(), *ma_n = Ma_.data();
  double* fa = fa_.data();
  // Sums: loads Du' (f^a_{n+1} + f^a_n); damping Du' ((1+a) C v_{n+1} + C v_n - a C v_{n-1});
  // 2T = v' M v; 2U = u' K u; the HHT term's (v_{n+1} + v_n)' (M a_{n+1} - M a_n),
  // a_{n+1}' M a_{n+1}, a_n' M a_n and Du' (K u_{n+1} - K u_{n-1}).
  Two w{0.0, 0.0}, d{0.0, 0.0}, t2{0.0, 0.0}, u2{0.0, 0.0}, ev{0.0, 0.0}, ea{0.0, 0.0}, eao{0.0, 0.0},
      ek{0.0, 0.0};
  const Two one_a{1.0 + a, 1.0 + a}, alpha{a, a};
  const auto at = [](const double* x, Eigen::Index i) { return Two{x[i], x[i + 1]}; };
  Eigen::Index i = 0;
  for (; i + 1 < n; i += 2) {
    const Two du = at(un, i) - at(uo, i);
    const Two fa_new{load_at(i), load_at(i + 1)};
    w += du * (fa_new + at(fa, i));
    fa[i] = fa_new[0];
    fa[i + 1] = fa_new[1];
    d += du * (one_a * at(cv, i) + at(cv_n, i) - alpha * at(cv_prev, i));
    t2 += at(vn, i) * at(mv, i);
    u2 += at(un, i) * at(ku, i);
    ev += (at(vn, i) + at(vo, i)) * (at(ma, i) - at(ma_n, i));
    ea += at(an, i) * at(ma, i);
    eao += at(ao, i) * at(ma_n, i);
    ek += du * (at(ku, i) - at(ku_prev, i));
  }
  for (; i < n; ++i) {  // an odd last row, in lane 0
    const double du = un[i] - uo[i];
    const double fa_new = load_at(i);
    w[0] += du * (fa_new + fa[i]);
    fa[i] = fa_new;
    d[0] += du * ((1.0 + a) * cv[i] + cv_n[i] - a * cv_prev[i]);
    t2[0] += vn[i] * mv[i];
    u2[0] += un[i] * ku[i];
    ev[0] += (vn[i] + vo[i]) * (ma[i] - ma_n[i]);
    ea[0] += an[i] * ma[i];
    eao[0] += ao[i] * ma_n[i];
    ek[0] += du * (ku[i] - ku_prev[i]);
  }
  const auto sum = [](Two x) { return x[0] + x[1]; };
  const double work = 0.5 * sum(w);
  const double damping = 0.5 * sum(d);
  const double e_hht = -h.dt * (h.gamma - 0.5) * 0.5 * sum(ev) +
                       0.5 * h.dt * h.dt * (h.beta - 0.5 * h.gamma) * (sum(ea) - sum(eao)) + 0.5 * a * sum(ek);
  e_.kinetic_J = 0.5 * sum(t2);
  e_.strain_J = 0.5 * sum(u2);
  e_.work_J += work;
  e_.damping_J += damping;
  e_.hht_J += e_hht;
  e_.abs_work_J += std::abs(work);
  e_.abs_damping_J += std::abs(damping);
  e_.abs_hht_J += std::abs(e_hht);
  Ku_prev_.swap(Ku_);
  Ku_.swap(p.Ku);
  Cv_prev_.swap(Cv_);
  Cv_.swap(p.Cv);
  Ma_.swap(p.Ma);
}

template class EnergyAccount<SparseMatrix>;
template class EnergyAccount<DenseMatrix>;

}  // namespace railvsi
