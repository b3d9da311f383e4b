// The modal rung for moving forces against Frýba's series and against the
// FE rung: the exact recurrence has no period error, so at a coarse time
// step it stays on the series where the HHT integration of the FE rung
// drifts.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "analysis/modal_moving_forces.hpp"
#include "core/input_error.hpp"
#include "fryba_series.hpp"
#include "generators/bridge_2d.hpp"
#include "integration/modal_recurrence.hpp"
#include "simulation/simulation.hpp"
#include "../support/worst_of.hpp"

namespace railvsi {
namespace {

using testing::Beam;
using testing::fryba_deflection;
using testing::kPi;

TEST(ModalRecurrence, FreeVibrationIsExactAtAnyStep) {
  // q(0) = 1, q'(0) = 0, no load: q = e^{-z w t}(cos wd t + z w / wd sin wd t).
  for (double zeta : {0.0, 0.02, 0.5}) {
    const double w = 2 * kPi * 5.0, dt = 0.3 / w * 7.0;  // w dt = 2.1: far beyond any HHT accuracy
    const ModalStep s = make_modal_step(w, zeta, dt);
    double q = 1.0, qd = 0.0;
    const double wd = w * std::sqrt(1 - zeta * zeta);
    for (int n = 1; n <= 50; ++n) {
      s.advance(q, qd, 0.0, 0.0);
      const double t = n * dt;
      const double exact = std::exp(-zeta * w * t) * (std::cos(wd * t) + zeta * w / wd * std::sin(wd * t));
      EXPECT_NEAR(q, exact, 1e-12) << "zeta " << zeta << " step " << n;
    }
  }
}

TEST(ModalRecurrence, RampLoadIsExact) {
  // q'' + w^2 q = r t from rest: q = r/w^2 (t - sin(w t)/w).
  const double w = 30.0, r = 4.0, dt = 0.05;
  const ModalStep s = make_modal_step(w, 0.0, dt);
  double q = 0.0, qd = 0.0;
  for (int n = 1; n <= 40; ++n) {
    const double a = s.advance(q, qd, r * (n - 1) * dt, r * n * dt);
    const double t = n * dt;
    EXPECT_NEAR(q, r / (w * w) * (t - std::sin(w * t) / w), 1e-13);
    EXPECT_NEAR(a, r / w * std::sin(w * t), 1e-10);
  }
}

struct Case {
  double speed_parameter;  // v / (2 f1 L)
  double damping_ratio;
};

class ModalMovingForce : public ::testing::TestWithParam<Case> {};

// The 25 m beam of the FE rung's Frýba test, with Rayleigh damping at f1
// and 9 f1; 4 modes up to 9.5 f1 kept by the modal rung; dt = 1/40 of the
// first period and at least 40 steps per crossing: coarse for HHT.
TEST_P(ModalMovingForce, MatchesFrybaSeriesAtACoarseStepWhereTheFeRungDrifts) {
  const Case c = GetParam();
  const Beam b{25.0, 7.0e10, 15000.0};
  const double P = 170e3;
  const double f1 = b.omega(1) / (2 * kPi);
  const double v = c.speed_parameter * 2 * f1 * b.L;
  const double crossing_s = b.L / v;
  const double wd1 = 2 * kPi * f1, wd2 = 2 * kPi * 9 * f1;
  const double a0 = 2 * c.damping_ratio * wd1 * wd2 / (wd1 + wd2), a1 = 2 * c.damping_ratio / (wd1 + wd2);
  const auto zeta = [&](int j) { return a0 / (2 * b.omega(j)) + a1 * b.omega(j) / 2; };

  Bridge2dOptions o;
  o.spans_m = {b.L};
  o.deck_EI_Nm2 = b.EI;
  o.deck_mass_kg_per_m = b.m;
  o.damping_ratio = c.damping_ratio;
  o.damping_f1_hz = f1;
  o.damping_f2_hz = 9 * f1;
  o.element_length_m = 0.5;
  Scene scene;
  scene.structure = make_bridge_2d(o);
  scene.train.moving_forces = {{0.0, P}};
  scene.speed_mps = v;
  scene.start_x_m = 0.0;
  const int steps = std::max(40, static_cast<int>(std::ceil(40.0 * crossing_s * f1)));
  scene.analysis.dt_s = crossing_s / steps;
  scene.analysis.duration_s = crossing_s;
  scene.analysis.hht = HhtParameters::from_alpha(c.damping_ratio == 0.0 ? 0.0 : -0.05);

  ModalMovingForceOptions mo;
  mo.max_frequency_hz = 9.5 * f1;  // bending modes 1..3 of the beam
  const ModalBasis basis(scene.structure, mo);
  ASSERT_EQ(basis.num_modes(), 3);  // mode 4 at 16 f1 is above the cut-off
  const Result fe = Simulation(scene).run();
  ASSERT_TRUE(fe.status.ok());
  // The series' midspan deflection, downward negative as the rung's.
  const auto deflection = [&](double t, int modes) { return -fryba_deflection(b, P, v, b.L / 2, t, modes, zeta); };
  struct Errors {
    double peak = 0.0, same = 0.0, all = 0.0;  // peak, error vs 3 modes, vs 60 modes
  };
  const auto errors = [&](const Result& r) {
    Errors e;
    const auto& t = r.histories.t_s;
    for (std::size_t k = 0; k < t.size(); ++k) {
      const double three = deflection(t[k], 3), sixty = deflection(t[k], 60);
      e.peak = railvsi::testing::worst_of(e.peak, std::abs(sixty));
      e.same = railvsi::testing::worst_of(e.same, std::abs(r.histories.deck_displacement_m[0][k] - three));
      e.all = railvsi::testing::worst_of(e.all, std::abs(r.histories.deck_displacement_m[0][k] - sixty));
    }
    return e;
  };
  const Result modes_only = run_modal_moving_forces(scene, basis, DeckOutputCorrection::kNone);
  const Result corrected = run_modal_moving_forces(scene, basis);
  ASSERT_TRUE(modes_only.status.ok()) << modes_only.status.message();
  ASSERT_TRUE(corrected.status.ok()) << corrected.status.message();
  ASSERT_EQ(modes_only.histories.t_s.size(), fe.histories.t_s.size());
  const Errors m = errors(modes_only), sc = errors(corrected), f = errors(fe);
  Scene fine = scene;
  fine.analysis.dt_s = scene.analysis.dt_s / 2;
  const Errors m_half = errors(run_modal_moving_forces(fine, basis, DeckOutputCorrection::kNone));
  std::printf("[modal] alpha=%.2f zeta=%.2f steps=%d, of the peak: modes alone vs 3-mode series %.2e (at dt/2 "
              "%.2e), vs 60 modes %.2e; with the static correction vs 60 modes %.2e; FE/HHT vs 60 modes %.2e\n",
              c.speed_parameter, c.damping_ratio, steps, m.same / m.peak,
              m_half.same / m.peak, m.all / m.peak, sc.all / sc.peak, f.all / f.peak);
  // No period error: what is left is the linear interpolation of the load
  // between steps, of second order in dt (measured <= 5.2e-4 of the peak
  // at 40 steps per crossing, and 3.9-4.0 times less at dt/2).
  EXPECT_LT(m.same, 1e-3 * m.peak);
  EXPECT_GT(m.same / m_half.same, 3.5);
  // Truncation at 3 modes costs 0.18-0.21 % of the peak midspan deflection.
  EXPECT_LT(m.all, 3e-3 * m.peak);
  // The static correction restores the modes above the cut-off but for
  // their dynamics: measured 5.1e-5 to 5.8e-4 of the peak (the rest is the
  // load's interpolation between steps, above), 3.1 to 42 times less than
  // the modes alone (1.8e-3 to 2.1e-3).
  EXPECT_LT(sc.all, 1e-3 * sc.peak);
  EXPECT_LT(sc.all, 0.4 * m.all);
  // At this step the FE/HHT rung (all modes) is further from the 60-mode
  // series than the modal rung with 3 (measured 3.3e-3 to 6.2e-3).
  EXPECT_GT(f.all, m.all);
}

// The 15 m span of the sweep (f0 = 5 Hz, 15 t/m, 1 %), three axles at
// 250 km/h, dt 1 ms.
Bridge2dOptions span_15m() {
  Bridge2dOptions o;
  o.spans_m = {15.0};
  o.deck_first_frequency_hz = 5.0;
  o.deck_mass_kg_per_m = 15000.0;
  o.damping_ratio = 0.01;
  return o;
}

Scene three_axles_on_span_15m() {
  Scene scene;
  scene.structure = make_bridge_2d(span_15m());
  scene.train.moving_forces = {{0.0, 170e3}, {3.0, 170e3}, {14.0, 170e3}};
  scene.speed_mps = 250 / 3.6;
  scene.analysis.dt_s = 1e-3;
  return scene;
}

TEST(ModalMovingForceBasis, OneSharedBasisGivesTheSameBitsAsABasisPerRun) {
  const Scene scene = three_axles_on_span_15m();
  ModalMovingForceOptions mo;
  mo.max_frequency_hz = 54.0;
  const ModalBasis basis(scene.structure, mo);
  EXPECT_EQ(basis.num_modes(), 3);  // 5, 20 and 45 Hz
  const Result shared = run_modal_moving_forces(scene, basis);
  const Result own = run_modal_moving_forces(scene, mo);
  ASSERT_TRUE(shared.status.ok());
  EXPECT_EQ(shared.histories.deck_displacement_m, own.histories.deck_displacement_m);
  EXPECT_EQ(shared.histories.deck_acceleration_mps2, own.histories.deck_acceleration_mps2);
  // A basis of another structure is refused, not silently used.
  Scene other = scene;
  other.structure = make_bridge_2d(span_15m());
  EXPECT_THROW(run_modal_moving_forces(other, basis), InputError);
}

TEST(ModalMovingForceBasis, SceneWithoutStaticCorrectionRunsTheModesAloneAndSaysSo) {
  Scene scene = three_axles_on_span_15m();
  ModalMovingForceOptions mo;
  mo.max_frequency_hz = 54.0;
  const ModalBasis basis(scene.structure, mo);
  const Result corrected = run_modal_moving_forces(scene, basis);
  scene.analysis.modal_static_correction = false;  // "analysis": {"static_correction": false}
  const Result alone = run_modal_moving_forces(scene, basis);
  const Result explicit_alone = run_modal_moving_forces(scene, basis, DeckOutputCorrection::kNone);
  EXPECT_TRUE(corrected.summary.fidelity.static_correction);
  EXPECT_NE(corrected.summary.fidelity.structure_backend.find("static correction"), std::string::npos);
  EXPECT_FALSE(alone.summary.fidelity.static_correction);
  EXPECT_EQ(alone.summary.fidelity.structure_backend.find("static correction"), std::string::npos);
  EXPECT_EQ(alone.histories.deck_displacement_m, explicit_alone.histories.deck_displacement_m);
  // The correction adds the dropped modes' static share: the histories differ.
  EXPECT_NE(alone.histories.deck_displacement_m, corrected.histories.deck_displacement_m);
}

TEST(ModalMovingForceBasis, ADeflectionBeyondTheSpanOverAHundredEndsUnstableAsOnTheFeRung) {
  // 20 m span, one 1 MN force crawling at 0.2 m/s (v / (2 f1 L) below
  // 0.005): the midspan deflection is the static P L^3 / (48 EI). The rule's limit is
  // max(0.1 m, 20 m / 100) = 0.2 m.
  const double L = 20.0, P = 1.0e6;
  const auto run_with_static_deflection = [&](double deflection_m) {
    Bridge2dOptions o;
    o.spans_m = {L};
    o.deck_EI_Nm2 = P * L * L * L / (48.0 * deflection_m);
    o.deck_mass_kg_per_m = 15000.0;
    o.damping_ratio = 0.02;
    o.output_points = {{"midspan", L / 2}};
    Scene scene;
    scene.structure = make_bridge_2d(o);
    scene.train.moving_forces = {{0.0, P}};
    scene.speed_mps = 0.2;
    scene.analysis.dt_s = 5e-3;
    ModalMovingForceOptions mo;
    mo.max_frequency_hz = 30.0;
    return run_modal_moving_forces(scene, mo);
  };
  const Result plausible = run_with_static_deflection(0.15);
  ASSERT_TRUE(plausible.status.ok()) << plausible.status.message();
  std::printf("[modal] crawling 1 MN, static 0.15 m: midspan peak %.6f m\n", plausible.summary.points.at(0).max_abs_displacement_m);
  // Measured 0.150003 m (2e-5 of the static value).
  EXPECT_NEAR(plausible.summary.points.at(0).max_abs_displacement_m, 0.15, 1e-4 * 0.15);
  const Result implausible = run_with_static_deflection(0.25);  // EI 40 % lower
  EXPECT_EQ(implausible.status.code(), StatusCode::kUnstable);
  EXPECT_NE(implausible.status.message().find("at output point 'midspan' exceeds 0.2 m (max(0.1 m, span/100))"),
            std::string::npos)
      << implausible.status.message();
}

INSTANTIATE_TEST_SUITE_P(SpeedParameters, ModalMovingForce,
                         ::testing::Values(Case{0.1, 0.0}, Case{0.3, 0.02}, Case{0.5, 0.0}, Case{1.0, 0.02}),
                         [](const ::testing::TestParamInfo<Case>& info) {
                           const long tenths = std::lround(info.param.speed_parameter * 10);
                           return "alpha" + std::to_string(tenths / 10) + "p" + std::to_string(tenths % 10) +
                                  (info.param.damping_ratio == 0.0 ? "_undamped" : "_damped2pct");
                         });

}  // namespace
}  // namespace railvsi
