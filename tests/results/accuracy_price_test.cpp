// vsi price's computation: the Richardson estimate, Pareto front and
// cheapest pick on rows with known answers, and the whole price of a moving
// force over a simply supported beam against Frýba's series.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "engine/fryba_series.hpp"
#include "generators/bridge_2d.hpp"
#include "planning/accuracy_price.hpp"
#include "planning/fidelity_ladder.hpp"
#include "price/price_analysis.hpp"

namespace railvsi {
namespace {

using testing::Beam;
using testing::fryba_deflection;
using testing::kPi;

TEST(RichardsonEstimate, RecoversTheErrorOfASecondOrderSequence) {
  // v(h) = 2 + 0.3 h^2 at h = 1, 2, 4: the exact error of v(1) is 0.3 / 2.
  const auto v = [](double h) { return 2.0 + 0.3 * h * h; };
  const RichardsonEstimate e = richardson_estimate(v(1), v(2), v(4));
  ASSERT_TRUE(e.asymptotic);
  EXPECT_NEAR(*e.order, 2.0, 1e-12);
  EXPECT_NEAR(*e.error, 0.3 / 2.0, 1e-12);
  EXPECT_NEAR(*e.last_change, (v(2) - v(1)) / v(1), 1e-15);
}

TEST(RichardsonEstimate, FirstOrderIsStillAsymptoticAndFourthOrderIsNot) {
  // p = 1: r = 2, at the edge of the criterion; the error of v(1) = 1 + 0.1 h is 0.1.
  const RichardsonEstimate first = richardson_estimate(1.1, 1.2, 1.4);
  ASSERT_TRUE(first.asymptotic);
  EXPECT_NEAR(*first.error, 0.1 / 1.0, 1e-12);
  // p = 4: r = 16 > 8, withheld.
  const RichardsonEstimate fourth = richardson_estimate(1.0 + 1e-3, 1.0 + 16e-3, 1.0 + 256e-3);
  EXPECT_FALSE(fourth.asymptotic);
  EXPECT_FALSE(fourth.error.has_value());
  EXPECT_NEAR(*fourth.order, 4.0, 1e-9);
}

TEST(RichardsonEstimate, OscillatingDifferencesAreNotAsymptotic) {
  const RichardsonEstimate e = richardson_estimate(1.0, 1.01, 0.99);
  EXPECT_FALSE(e.asymptotic);
  EXPECT_FALSE(e.error.has_value());
  EXPECT_FALSE(e.order.has_value());
}

TEST(RichardsonEstimate, EqualValuesAreConvergedToRoundOff) {
  const RichardsonEstimate e = richardson_estimate(3.0, 3.0, 3.0);
  ASSERT_TRUE(e.asymptotic);
  EXPECT_EQ(*e.error, 0.0);
}

PriceRow row(int rung, double dt_s, double cpu_s, std::optional<double> disp) {
  PriceRow r;
  r.rung = rung;
  r.dt_s = dt_s;
  r.cpu_s = cpu_s;
  r.values["deck_displacement_m"] = disp;
  return r;
}

TEST(PriceErrors, AgainstTheFinestRunOfTheMostCompleteRung) {
  std::vector<PriceRow> rows = {row(0, 1e-3, 0.1, 1.10), row(0, 5e-4, 0.2, 1.05), row(1, 1e-3, 1.0, 1.02),
                                row(1, 5e-4, 2.0, 1.00), row(1, 2.5e-4, 4.0, std::nullopt)};
  rows[4].status = "unstable";  // the finest run failed: the next finest ok run is the reference
  const PriceReference ref = price_errors(rows);
  ASSERT_EQ(ref.row, std::optional<std::size_t>(3));
  EXPECT_NEAR(*rows[0].errors.at("deck_displacement_m"), 0.10, 1e-12);
  EXPECT_NEAR(*rows[2].errors.at("deck_displacement_m"), 0.02, 1e-12);
  EXPECT_EQ(*rows[3].errors.at("deck_displacement_m"), 0.0);
  EXPECT_FALSE(rows[4].errors.at("deck_displacement_m").has_value());
  // Wheel quantities have no value in these rows: no error either.
  EXPECT_FALSE(rows[0].errors.at("unloading_ratio").has_value());

  // Pareto front of |error| against CPU: 0.1 s (10 %), 0.2 s (5 %), 1.0 s
  // (2 %), 2.0 s (0 %); every row improves on all cheaper ones.
  EXPECT_EQ(pareto_fronts(rows).at("deck_displacement_m"), (std::vector<std::size_t>{0, 1, 2, 3}));
  rows[1].errors["deck_displacement_m"] = 0.2;  // now worse than the cheaper row 0: off the front
  // But row 0 (1 ms, 10 %) is then better than its own rung's 0.5 ms (20 %):
  // its error is not monotone in dt, a lucky step, so it is off the front
  // and row 1, the cheapest honest row, is on it.
  EXPECT_EQ(pareto_fronts(rows).at("deck_displacement_m"), (std::vector<std::size_t>{1, 2, 3}));
  EXPECT_EQ(cheapest_within(rows, 0.05).at("deck_displacement_m"), std::optional<std::size_t>(2));
  EXPECT_EQ(cheapest_within(rows, 0.01).at("deck_displacement_m"), std::optional<std::size_t>(3));
  // Not the lucky row 0 either: row 1 is the cheapest honest row within 50 %.
  EXPECT_EQ(cheapest_within(rows, 0.5).at("deck_displacement_m"), std::optional<std::size_t>(1));
}

TEST(PriceErrors, ZeroReferenceGivesZeroOnlyForZero) {
  std::vector<PriceRow> rows = {row(0, 1e-3, 0.1, 0.0), row(0, 2e-3, 0.05, 0.01), row(1, 1e-3, 1.0, 0.0)};
  price_errors(rows);
  EXPECT_EQ(*rows[0].errors.at("deck_displacement_m"), 0.0);
  EXPECT_FALSE(rows[1].errors.at("deck_displacement_m").has_value());
}

TEST(FidelityLadder, RungScenesOfAMultibodyScene) {
  // A moving-force rung turns wheels into their static loads; interaction
  // rungs set their contact law.
  const auto& ladder = fidelity_ladder();
  ASSERT_GE(ladder.size(), 5u);
  EXPECT_EQ(ladder.back().model_name(), "interaction");
  EXPECT_EQ(ladder.back().contact_law, "hertz");
  EXPECT_EQ(ladder.front().structure_name(), "modal");
}

// A 170 kN force crossing a 25 m simply supported beam with 2 % Rayleigh
// damping (matched at f1 and 9 f1; the series gets the same modal ratios)
// and the default HHT alpha = -0.05. The run ends as the force leaves the
// beam: Frýba's series holds while the force is on it. (Undamped with
// alpha = 0 the FE rung's peak does not converge regularly: the force's
// entry excites the mesh's high modes, which nothing damps, and the peak
// samples them; the Richardson estimate is then rightly withheld.)
TEST(AccuracyPrice, ErrorsOfEachRungMatchFrybaWithinTheRichardsonAccuracy) {
  const Beam b{25.0, 7.0e10, 15000.0};
  const double P = 170e3;
  const double f1 = b.omega(1) / (2.0 * kPi);
  const double v = 0.2 * 2.0 * f1 * b.L;  // speed parameter 0.2
  const double crossing_s = b.L / v;

  Bridge2dOptions o;
  o.spans_m = {b.L};
  o.deck_EI_Nm2 = b.EI;
  o.deck_mass_kg_per_m = b.m;
  o.damping_ratio = 0.02;
  o.damping_f1_hz = f1;
  o.damping_f2_hz = 9.0 * f1;
  const double w1 = 2.0 * kPi * f1, w2 = 2.0 * kPi * 9.0 * f1;
  const double a0 = 2.0 * 0.02 * w1 * w2 / (w1 + w2), a1 = 2.0 * 0.02 / (w1 + w2);
  const auto zeta = [&](int j) { return a0 / (2.0 * b.omega(j)) + a1 * b.omega(j) / 2.0; };
  o.element_length_m = 0.25;  // 100 elements: the FE's own error on the first modes is far below the dt errors
  o.output_points = {{"mid", b.L / 2.0}};
  Scene scene;
  scene.structure = make_bridge_2d(o);
  scene.train.name = "one force";
  scene.train.moving_forces = {{0.0, P}};
  scene.speed_mps = v;
  scene.start_x_m = 0.0;
  scene.analysis.duration_s = crossing_s;

  PriceOptions po;
  po.f0_hz = f1;
  po.f3_hz = 9.0 * f1;
  po.threads = 2;
  const PriceReport p = price_scene(scene, po);
  ASSERT_TRUE(p.reference.row.has_value());
  const PriceRow& ref = p.rows[*p.reference.row];
  EXPECT_EQ(ref.model, "moving_forces");
  EXPECT_EQ(ref.structure, "fe");
  const std::string q = "deck_displacement_m";
  const RichardsonEstimate& rich = p.reference.richardson.at(q);
  for (const PriceRow& r : p.rows)
    std::printf("[price-fryba] %s / %s dt %.4g s: %.12e\n", r.model.c_str(), r.structure.c_str(), r.dt_s,
                *r.values.at(q));

  // The series' peak over the crossing (60 modes: the tail is < 1e-5 of the
  // first term), on a grid 100 times finer than the finest run, then
  // refined by a parabola through the three samples around the maximum.
  const int n = static_cast<int>(std::ceil(crossing_s / (ref.dt_s / 100.0)));
  const auto w = [&](double t) { return std::abs(fryba_deflection(b, P, v, b.L / 2.0, t, 60, zeta)); };
  int k_max = 0;
  double w_max = 0.0;
  for (int k = 0; k <= n; ++k) {
    const double wk = w(crossing_s * k / n);
    if (wk > w_max) {
      w_max = wk;
      k_max = k;
    }
  }
  double peak = w_max;
  if (k_max > 0 && k_max < n) {
    const double h = crossing_s / n, t = crossing_s * k_max / n;
    const double a = w(t - h), c = w(t + h);
    peak = w_max + (a - c) * (a - c) / (8.0 * (2.0 * w_max - a - c));
  }

  const double e_ref_true = (*ref.values.at(q) - peak) / peak;
  std::printf("[price-fryba] series peak %.12e, reference's true error %.3e\n", peak, e_ref_true);
  ASSERT_TRUE(rich.asymptotic) << "order " << rich.order.value_or(NAN);
  std::printf("[price-fryba] peak series %.9e, reference %.9e (dt %.3g s): true error %.3e, Richardson %.3e "
              "(order %.2f)\n",
              peak, *ref.values.at(q), ref.dt_s, e_ref_true, *rich.error, *rich.order);
  // The reference's own error: Richardson estimates it to within its own
  // size (the stated accuracy: the true error lies within [0, 2] x the
  // estimate, i.e. |true - estimate| <= |estimate|). Measured: estimate
  // 2.58e-6 (observed order 1.77), true error 1.84e-6 against the series
  // (60 modes, parabola-refined peak); the mesh (100 elements) and the
  // series' tail are far below that.
  const double accuracy = std::abs(*rich.error);
  EXPECT_NEAR(e_ref_true, *rich.error, accuracy);

  // Every row: the reported error (against the reference) matches the
  // error against the series within that accuracy, to first order in the
  // errors ((v - v_ref)/v_ref - (v - v*)/v* = -e_ref (1 + e) / (1 + e_ref)).
  int compared = 0;
  for (const PriceRow& r : p.rows) {
    ASSERT_TRUE(r.ok()) << r.message;
    const double reported = *r.errors.at(q);
    const double against_series = (*r.values.at(q) - peak) / peak;
    std::printf("[price-fryba] %s / %s dt %.4g s: reported %+.4e, against the series %+.4e\n", r.model.c_str(),
                r.structure.c_str(), r.dt_s, reported, against_series);
    EXPECT_NEAR(reported, against_series, accuracy * (1.0 + std::abs(against_series)) + 1e-12)
        << r.model << " / " << r.structure << " at " << r.dt_s;
    ++compared;
  }
  EXPECT_EQ(compared, 10);  // two moving-force rungs x five steps
}

}  // namespace
}  // namespace railvsi
