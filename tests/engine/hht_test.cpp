// HHT-alpha integrator (integration/hht.hpp) on small dense systems driven
// by a loop written here: order of accuracy, energy conservation for
// alpha = 0, high-frequency dissipation for alpha < 0, the stability check
// of the parameters, and one run through Simulation.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "generators/bridge_2d.hpp"
#include "integration/hht.hpp"
#include "simulation/simulation.hpp"
#include "../support/worst_of.hpp"

namespace railvsi {
namespace {

constexpr double kPi = std::numbers::pi;

// Free vibration M a + C v + K u = 0 with HHT: K_bar u_{n+1} = history rhs
// (no loads), K_bar = c0 M + (1+alpha) c3 C + (1+alpha) K, factorized once
// (dense LLT). Calls observe(n, state) after every step.
class DenseHht {
 public:
  DenseHht(const HhtParameters& p, double dt, DenseMatrix M, DenseMatrix C, DenseMatrix K)
      : h_(p, dt), M_(std::move(M)), C_(std::move(C)), K_(std::move(K)) {
    const DenseMatrix Kbar = h_.mass_factor() * M_ + h_.damping_factor() * C_ + h_.stiffness_factor() * K_;
    llt_.compute(Kbar);
  }
  // Initial state with the acceleration from the equation of motion.
  KinematicState start(const Vector& u0, const Vector& v0) const {
    KinematicState s;
    s.u = u0;
    s.v = v0;
    s.a = M_.llt().solve(-C_ * v0 - K_ * u0);
    return s;
  }
  void step(KinematicState& s) {
    hht_history_rhs(h_, M_, C_, K_, s, rhs_, work_);
    u_new_ = llt_.solve(rhs_);
    hht_update(h_, u_new_, s);
  }
  template <class Observe>
  void run(KinematicState& s, long steps, Observe observe) {
    for (long n = 1; n <= steps; ++n) {
      step(s);
      observe(n, s);
    }
  }
  void run(KinematicState& s, long steps) {
    run(s, steps, [](long, const KinematicState&) {});
  }

 private:
  HhtCoefficients h_;
  DenseMatrix M_, C_, K_;
  Eigen::LLT<DenseMatrix> llt_;
  Vector rhs_, work_, u_new_;
};

DenseMatrix scalar(double x) { return DenseMatrix::Constant(1, 1, x); }

// Error at t = T of a SDOF (m = 1, w = 2 pi, damping ratio zeta) released
// from u = 1, v = 0, in the state norm sqrt(du^2 + (dv/w)^2) (first order in
// the phase error, so the observed order is that of the scheme).
double sdof_error(const HhtParameters& p, double zeta, double T, int steps) {
  const double w = 2.0 * kPi;
  DenseHht hht(p, T / steps, scalar(1.0), scalar(2.0 * zeta * w), scalar(w * w));
  KinematicState s = hht.start(Vector::Ones(1), Vector::Zero(1));
  hht.run(s, steps);
  const double wd = w * std::sqrt(1.0 - zeta * zeta), e = std::exp(-zeta * w * T);
  const double u = e * (std::cos(wd * T) + zeta * w / wd * std::sin(wd * T));
  const double v = -e * w * w / wd * std::sin(wd * T);
  return std::hypot(s.u[0] - u, (s.v[0] - v) / w);
}

struct OrderCase {
  double alpha;
  double zeta;
};

class HhtOrder : public ::testing::TestWithParam<OrderCase> {};

TEST_P(HhtOrder, ErrorAtFixedTimeFallsFourfoldWhenStepHalves) {
  const auto [alpha, zeta] = GetParam();
  const HhtParameters p = HhtParameters::from_alpha(alpha);
  // T = 1.3 periods (not a multiple of the period); 130, 260, 520 steps:
  // w dt <= 0.063, well inside the asymptotic range.
  const double T = 1.3;
  const double e1 = sdof_error(p, zeta, T, 130), e2 = sdof_error(p, zeta, T, 260),
               e3 = sdof_error(p, zeta, T, 520);
  const double r1 = std::log2(e1 / e2), r2 = std::log2(e2 / e3);
  std::printf("[hht order] alpha=%.4f zeta=%.2f errors %.3e %.3e %.3e, observed orders %.4f %.4f\n",
              alpha, zeta, e1, e2, e3, r1, r2);
  // Second order: log2 of the error ratio in [1.9, 2.1].
  EXPECT_GE(r1, 1.9);
  EXPECT_LE(r1, 2.1);
  EXPECT_GE(r2, 1.9);
  EXPECT_LE(r2, 2.1);
}

// alpha = 0 (the trapezoidal rule); HHT is second order
// for every alpha in [-1/3, 0] with the consistent beta, gamma (Hilber,
// Hughes & Taylor 1977), so -0.05 and -1/3 are checked too.
INSTANTIATE_TEST_SUITE_P(Cases, HhtOrder,
                         ::testing::Values(OrderCase{0.0, 0.0}, OrderCase{0.0, 0.05},
                                           OrderCase{-0.05, 0.0}, OrderCase{-0.05, 0.05},
                                           OrderCase{-1.0 / 3.0, 0.0}, OrderCase{-1.0 / 3.0, 0.05}),
                         [](const ::testing::TestParamInfo<OrderCase>& info) {
                           const char* a = info.param.alpha == 0.0 ? "alpha0"
                                           : info.param.alpha == -0.05 ? "alpha_minus0p05"
                                                                       : "alpha_minus1over3";
                           return std::string(a) + (info.param.zeta == 0.0 ? "_undamped" : "_damped");
                         });

// Two DOFs, coupled in physical coordinates (non-diagonal M and K), with
// natural frequencies 1 Hz and 200 Hz: K = M Phi diag(w^2) Phi^T M with
// Phi^T M Phi = I (Phi = L^-T Q, M = L L^T, Q a rotation).
struct TwoDof {
  DenseMatrix M, K, Phi;
  double w_low = 2.0 * kPi * 1.0, w_high = 2.0 * kPi * 200.0;
  TwoDof() {
    M.resize(2, 2);
    M << 3.0, 0.8, 0.8, 1.5;
    const DenseMatrix L = M.llt().matrixL();
    const double th = 0.6;
    DenseMatrix Q(2, 2);
    Q << std::cos(th), -std::sin(th), std::sin(th), std::cos(th);
    Phi = L.transpose().triangularView<Eigen::Upper>().solve(Q);
    Vector w2(2);
    w2 << w_low * w_low, w_high * w_high;
    K = M * Phi * w2.asDiagonal() * Phi.transpose() * M;
    K = 0.5 * (K + K.transpose());
  }
  // Modal amplitude sqrt(q^2 + (q'/w)^2) of each mode.
  Vector amplitudes(const KinematicState& s) const {
    const Vector q = Phi.transpose() * M * s.u, qd = Phi.transpose() * M * s.v;
    Vector a(2);
    a << std::hypot(q[0], qd[0] / w_low), std::hypot(q[1], qd[1] / w_high);
    return a;
  }
};

TEST(HhtTwoDof, ModalConstructionHasTheIntendedFrequencies) {
  const TwoDof sys;
  const Eigen::GeneralizedSelfAdjointEigenSolver<DenseMatrix> eig(sys.K, sys.M);
  EXPECT_NEAR(std::sqrt(eig.eigenvalues()[0]) / sys.w_low, 1.0, 1e-10);
  EXPECT_NEAR(std::sqrt(eig.eigenvalues()[1]) / sys.w_high, 1.0, 1e-10);
  EXPECT_GT(std::abs(sys.M(0, 1)), 0.0);
  EXPECT_GT(std::abs(sys.K(0, 1)), 0.0);
}

TEST(HhtTwoDof, AlphaZeroConservesEnergyOverTenThousandSteps) {
  const TwoDof sys;
  const double dt = 0.05 / sys.w_low;  // w_low dt = 0.05, w_high dt = 10
  DenseHht hht(HhtParameters::from_alpha(0.0), dt, sys.M, DenseMatrix::Zero(2, 2), sys.K);
  // Both modes excited: u0 = Phi (1, 0.01), v0 = Phi (0, 0.01 w_high).
  const Vector u0 = sys.Phi * Vector::Unit(2, 0) + 0.01 * sys.Phi * Vector::Unit(2, 1);
  const Vector v0 = 0.01 * sys.w_high * sys.Phi * Vector::Unit(2, 1);
  KinematicState s = hht.start(u0, v0);
  const auto energy = [&](const KinematicState& st) {
    return 0.5 * st.v.dot(sys.M * st.v) + 0.5 * st.u.dot(sys.K * st.u);
  };
  const double E0 = energy(s);
  double worst = 0.0;
  hht.run(s, 10000, [&](long, const KinematicState& st) {
    worst = railvsi::testing::worst_of(worst, std::abs(energy(st) - E0) / E0);
  });
  std::printf("[hht energy] max |E - E0| / E0 over 10000 steps: %.3e\n", worst);
  // The trapezoidal rule conserves this energy exactly; 1e-10 leaves room
  // for round-off only.
  EXPECT_LT(worst, 1e-10);
  // Not conserved by one mode swallowing the other: each modal energy is
  // conserved too (the modes decouple), the high mode's at w_high dt = 10.
  EXPECT_NEAR(sys.amplitudes(s)[0], 1.0, 1e-9);
  EXPECT_NEAR(sys.amplitudes(s)[1] / std::hypot(0.01, 0.01), 1.0, 1e-9);
}

TEST(HhtTwoDof, NegativeAlphaDampsTheHighModeAndKeepsTheLowMode) {
  const TwoDof sys;
  const double dt = 0.05 / sys.w_low;  // w_low dt = 0.05, w_high dt = 10
  DenseHht hht(HhtParameters::from_alpha(-0.3), dt, sys.M, DenseMatrix::Zero(2, 2), sys.K);
  const Vector u0 = sys.Phi * Vector::Ones(2);  // unit amplitude in both modes
  KinematicState s = hht.start(u0, Vector::Zero(2));
  const Vector A0 = sys.amplitudes(s);
  const long steps = 20;  // 1 rad of the low mode's phase
  hht.run(s, steps);
  const Vector A = sys.amplitudes(s);
  const double low = A[0] / A0[0], high = A[1] / A0[1];
  std::printf("[hht dissipation] alpha=-0.3 after %ld steps: low mode %.6f, high mode %.3e "
              "(rho(0.05)^n = %.6f, rho(10)^n = %.3e)\n",
              steps, low, high, std::pow(hht_spectral_radius(HhtParameters::from_alpha(-0.3), 0.05), steps),
              std::pow(hht_spectral_radius(HhtParameters::from_alpha(-0.3), 10.0), steps));
  EXPECT_LT(high, 1e-2);
  EXPECT_GT(low, 0.99);
  // The same run with alpha = 0 keeps both (no numerical dissipation).
  DenseHht trap(HhtParameters::from_alpha(0.0), dt, sys.M, DenseMatrix::Zero(2, 2), sys.K);
  KinematicState s0 = trap.start(u0, Vector::Zero(2));
  trap.run(s0, steps);
  const Vector A_trap = sys.amplitudes(s0);
  EXPECT_NEAR(A_trap[0] / A0[0], 1.0, 1e-12);
  EXPECT_NEAR(A_trap[1] / A0[1], 1.0, 1e-12);
}

TEST(HhtParameters, ConsistentParametersAreAccepted) {
  for (double alpha : {0.0, -0.05, -0.1, -0.2, -1.0 / 3.0}) {
    const HhtParameters p = HhtParameters::from_alpha(alpha);
    EXPECT_DOUBLE_EQ(p.beta, 0.25 * (1.0 - alpha) * (1.0 - alpha));
    EXPECT_DOUBLE_EQ(p.gamma, 0.5 - alpha);
    const auto problem = hht_stability_problem(p);
    EXPECT_FALSE(problem.has_value()) << "alpha " << alpha << ": " << *problem;
    // Accepted without a scan (the 1977 proof); the scan agrees: the
    // spectral radius never exceeds 1 over omega*dt = 1e-3 ... 1e7.
    double rho = 0.0;
    for (double lg = -3.0; lg <= 7.0; lg += 0.01) rho = railvsi::testing::worst_of(rho, hht_spectral_radius(p, std::pow(10.0, lg)));
    EXPECT_LE(rho, 1.0 + 1e-9) << "alpha " << alpha;
  }
  // A pair a rounding away from the consistent one is scanned (and passes).
  const HhtParameters near{-0.05, std::nextafter(0.275625, 1.0), 0.55};
  EXPECT_FALSE(hht_stability_problem(near).has_value());
  // Not a number is refused (the scan would not see it).
  EXPECT_TRUE(hht_stability_problem({-0.05, 0.275625, std::nan("")}).has_value());
  EXPECT_TRUE(hht_stability_problem({-0.05, std::nan(""), 0.55}).has_value());
  EXPECT_TRUE(hht_stability_problem({std::nan(""), 0.275625, 0.55}).has_value());
  // Hilber, Hughes & Taylor (1977): alpha = -0.05 gives beta = 0.275625, gamma = 0.55.
  const HhtParameters p = HhtParameters::from_alpha(-0.05);
  EXPECT_NEAR(p.beta, 0.275625, 1e-15);
  EXPECT_NEAR(p.gamma, 0.55, 1e-15);
}

TEST(HhtParameters, PapersPrintedBetaGammaAreRejectedEitherWayRound) {
  // The paper's example prints beta = 9/20, gamma = 9025/40000 for
  // alpha = -0.05: gamma < 1/2.
  const HhtParameters printed{-0.05, 9.0 / 20.0, 9025.0 / 40000.0};
  const HhtParameters swapped{-0.05, 9025.0 / 40000.0, 9.0 / 20.0};
  EXPECT_TRUE(hht_stability_problem(printed).has_value());
  EXPECT_TRUE(hht_stability_problem(swapped).has_value());
  // Both amplify: spectral radius above 1 somewhere.
  double rho_printed = 0.0, rho_swapped = 0.0;
  for (double lg = -2.0; lg <= 4.0; lg += 0.1) {
    rho_printed = railvsi::testing::worst_of(rho_printed, hht_spectral_radius(printed, std::pow(10.0, lg)));
    rho_swapped = railvsi::testing::worst_of(rho_swapped, hht_spectral_radius(swapped, std::pow(10.0, lg)));
  }
  EXPECT_GT(rho_printed, 1.0 + 1e-6);
  EXPECT_GT(rho_swapped, 1.0 + 1e-6);
}

TEST(HhtParameters, ConditionallyStableNewmarkIsRejected) {
  // Newmark gamma = 1/2, beta = 0.1: stable only for w dt < 1/sqrt(gamma/2 - beta) = 2.582.
  const HhtParameters newmark{0.0, 0.1, 0.5};
  EXPECT_TRUE(hht_stability_problem(newmark).has_value());
  EXPECT_LE(hht_spectral_radius(newmark, 2.5), 1.0 + 1e-12);
  EXPECT_GT(hht_spectral_radius(newmark, 2.7), 1.0 + 1e-6);
}

TEST(HhtParameters, SpectralRadiusIsBoundedByOneAndTendsToTheKnownHighFrequencyLimit) {
  for (double alpha : {0.0, -0.05, -0.1, -0.2, -0.3, -1.0 / 3.0}) {
    const HhtParameters p = HhtParameters::from_alpha(alpha);
    for (double lg = -3.0; lg <= 6.0; lg += 0.05)
      ASSERT_LE(hht_spectral_radius(p, std::pow(10.0, lg)), 1.0 + 1e-12) << "alpha " << alpha;
    // rho_inf = (1 + alpha) / (1 - alpha) (Hilber, Hughes & Taylor 1977).
    const double rho_inf = (1.0 + alpha) / (1.0 - alpha);
    EXPECT_NEAR(hht_spectral_radius(p, 1e5), rho_inf, 1e-3) << "alpha " << alpha;
  }
}

TEST(HhtParameters, SpectralRadiusMatchesTheAmplificationOfTheLoopAbove) {
  // The amplification matrix of DenseHht built column by column from unit
  // (u, v, a) states; its spectral radius equals hht_spectral_radius.
  for (double alpha : {0.0, -0.05, -1.0 / 3.0}) {
    const HhtParameters p = HhtParameters::from_alpha(alpha);
    for (double Omega : {0.1, 1.0, 10.0, 1000.0}) {
      const double dt = 0.01, w = Omega / dt;
      DenseHht hht(p, dt, scalar(1.0), scalar(0.0), scalar(w * w));
      Eigen::Matrix3d A;
      for (int j = 0; j < 3; ++j) {
        KinematicState s;
        s.u = Vector::Zero(1);
        s.v = Vector::Zero(1);
        s.a = Vector::Zero(1);
        (j == 0 ? s.u : j == 1 ? s.v : s.a)[0] = 1.0;
        hht.step(s);
        A.col(j) << s.u[0], s.v[0], s.a[0];
      }
      // The (u, v, a) scaling (dt = 0.01 here, 1 in the engine) does not
      // change eigenvalues, only round-off: near alpha = -1/3 and large Omega
      // the roots nearly coincide and their round-off grows like sqrt(eps)
      // (4e-9 observed at Omega = 1000), hence 1e-7.
      const double rho = A.eigenvalues().cwiseAbs().maxCoeff();
      EXPECT_NEAR(rho, hht_spectral_radius(p, Omega), 1e-7) << "alpha " << alpha << " Omega " << Omega;
    }
  }
}

TEST(HhtSimulation, StationaryForceAtMidspanKeepsTheStaticDeflectionExactly) {
  // Speed 0: the run starts from static equilibrium and must stay there,
  // with HHT alpha = -0.05 and Rayleigh damping (every term of the HHT
  // right-hand side is active).
  const double L = 25.0, EI = 7.0e10, m = 15000.0, P = 170e3;
  Bridge2dOptions o;
  o.spans_m = {L};
  o.deck_EI_Nm2 = EI;
  o.deck_mass_kg_per_m = m;
  o.damping_ratio = 0.02;
  o.element_length_m = 0.5;
  Scene scene;
  scene.structure = make_bridge_2d(o);
  scene.train.moving_forces = {{0.0, P}};
  scene.speed_mps = 0.0;
  scene.start_x_m = 0.5 * L;
  scene.analysis.dt_s = 1e-3;
  scene.analysis.duration_s = 1.0;
  const Result r = Simulation(scene).run();
  ASSERT_TRUE(r.status.ok()) << r.status.message();
  const double expected = -P * L * L * L / (48.0 * EI);
  double worst_u = 0.0, worst_a = 0.0;
  for (std::size_t k = 0; k < r.histories.t_s.size(); ++k) {
    worst_u = railvsi::testing::worst_of(worst_u, std::abs(r.histories.deck_displacement_m[0][k] / expected - 1.0));
    worst_a = railvsi::testing::worst_of(worst_a, std::abs(r.histories.deck_acceleration_mps2[0][k]));
  }
  EXPECT_EQ(r.histories.t_s.size(), 1001u);
  // Static deflection exact to round-off (1e-9 relative; cubic Hermite
  // elements are nodally exact for a nodal point load); no transient.
  EXPECT_LT(worst_u, 1e-9);
  // Acceleration: a transient would give |a| ~ w1^2 * |u| ~ 1 m/s^2.
  EXPECT_LT(worst_a, 1e-6);
}

}  // namespace
}  // namespace railvsi

TEST(HhtParameters, PeriodErrorOfTheTrapezoidalRuleIsTheClosedForm) {
  // alpha = 0: the amplification has the phase 2 atan(Omega / 2), so the
  // numerical period is Omega / (2 atan(Omega / 2)) times the exact one.
  const railvsi::HhtParameters p = railvsi::HhtParameters::from_alpha(0.0);
  for (double omega_dt : {0.05, 0.163, 0.314, 1.0, 2.0}) {
    const double exact = omega_dt / (2.0 * std::atan(0.5 * omega_dt)) - 1.0;
    EXPECT_NEAR(railvsi::hht_period_error(p, omega_dt), exact, 1e-12 + 1e-9 * exact) << omega_dt;
  }
  // alpha = -0.05 lengthens the period more than the trapezoidal rule; at 20
  // steps per period by 0.93 % (the value the earlier policy quoted).
  const railvsi::HhtParameters h = railvsi::HhtParameters::from_alpha(-0.05);
  const double e20 = railvsi::hht_period_error(h, 2.0 * M_PI / 20.0);
  EXPECT_GT(e20, railvsi::hht_period_error(p, 2.0 * M_PI / 20.0));
  EXPECT_NEAR(e20, 0.0093, 0.0003);
}
