// The energy account's one pass over the rows (simulation/energy_balance.cpp)
// against the balance's terms written out with Eigen's products and dot
// products, step by step on the track model's matrices with random states
// and loads: the same totals to rounding.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>

#include "simulation/energy_balance.hpp"
#include "test_scenes.hpp"

namespace railvsi {
namespace {

// The balance's terms of one step from t_n to t_{n+1}, as
// simulation/energy_balance.hpp derives them.
struct Reference {
  EnergyTotals e;
  Vector Ku_prev, Ku, Cv_prev, Cv, Ma, fa;
  void step(const HhtCoefficients& h, const SparseMatrix& M, const SparseMatrix& C, const SparseMatrix& K,
            const KinematicState& old, const KinematicState& now, const Vector& f_alpha) {
    const double a = h.alpha;
    const Vector du = now.u - old.u;
    const Vector Ku_new = K * now.u, Cv_new = C * now.v, Ma_new = M * now.a, Mv_new = M * now.v;
    const double w = 0.5 * du.dot(f_alpha + fa);
    const double d = 0.5 * du.dot((1.0 + a) * Cv_new + Cv - a * Cv_prev);
    const double e_hht = -h.dt * (h.gamma - 0.5) * 0.5 * (now.v + old.v).dot(Ma_new - Ma) +
                         0.5 * h.dt * h.dt * (h.beta - 0.5 * h.gamma) * (now.a.dot(Ma_new) - old.a.dot(Ma)) +
                         0.5 * a * du.dot(Ku_new - Ku_prev);
    e.kinetic_J = 0.5 * now.v.dot(Mv_new);
    e.strain_J = 0.5 * now.u.dot(Ku_new);
    e.work_J += w;
    e.damping_J += d;
    e.hht_J += e_hht;
    Ku_prev = Ku;
    Ku = Ku_new;
    Cv_prev = Cv;
    Cv = Cv_new;
    Ma = Ma_new;
    fa = f_alpha;
  }
};

KinematicState random_state(Eigen::Index n) {
  KinematicState s;
  s.resize(n);
  s.u = 1e-3 * Vector::Random(n);
  s.v = 1e-2 * Vector::Random(n);
  s.a = Vector::Random(n);
  return s;
}

double relative(double x, double ref, double scale) { return std::abs(x - ref) / scale; }

TEST(EnergyAccountOnePass, EqualsTheTermsWrittenOutWithEigen) {
  const auto s = testing::small_viaduct_with_dip(100.0, 0.01).structure;
  const SparseMatrix &M = s->M(), &C = s->C(), &K = s->K();
  const Eigen::Index n = s->num_dofs();  // odd or even: the last row's lane is checked either way
  const HhtCoefficients h(HhtParameters::from_alpha(-0.1), 2.5e-4);
  std::srand(11);
  KinematicState old = random_state(n);
  Vector f_old = 1e4 * Vector::Random(n);
  EnergyAccount<SparseMatrix> given_fa(M, C, K, old, f_old), given_f(M, C, K, old, f_old);
  Reference ref;
  ref.Ku = ref.Ku_prev = K * old.u;
  ref.Cv = ref.Cv_prev = C * old.v;
  ref.Ma = M * old.a;
  ref.fa = f_old;
  double worst = 0.0;
  for (int step = 0; step < 20; ++step) {
    const KinematicState now = random_state(n);
    const Vector f_new = 1e4 * Vector::Random(n);
    const Vector f_alpha = (1.0 + h.alpha) * f_new - h.alpha * f_old;
    ref.step(h, M, C, K, old, now, f_alpha);
    StateProducts p{K * now.u, C * now.v, M * now.v, M * now.a};
    StateProducts q = p;
    given_fa.step(h, old, now, f_alpha, p);
    given_f.step(h, old, now, f_new, f_old, q);
    // Each term against its reference, relative to the largest term of the step.
    const EnergyTotals& r = ref.e;
    const double scale = std::max({std::abs(r.kinetic_J), std::abs(r.strain_J), std::abs(r.work_J),
                                   std::abs(r.damping_J), std::abs(r.hht_J)});
    for (const EnergyAccount<SparseMatrix>* account : {&given_fa, &given_f}) {
      const EnergyTotals& t = account->totals();
      for (const double d : {relative(t.kinetic_J, r.kinetic_J, scale), relative(t.strain_J, r.strain_J, scale),
                             relative(t.work_J, r.work_J, scale), relative(t.damping_J, r.damping_J, scale),
                             relative(t.hht_J, r.hht_J, scale)}) {
        ASSERT_TRUE(std::isfinite(d));
        worst = std::max(worst, d);
      }
    }
    old = now;
    f_old = f_new;
  }
  // Measured (2026-11-28): 1.33e-15, another summation order; tolerance 3x that.
  EXPECT_LE(worst, 4e-15);
}

}  // namespace
}  // namespace railvsi
