// Static influence lines against Euler-Bernoulli closed forms on a simply
// supported span without track (the rail line is the deck itself).
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "analysis/static_influence.hpp"
#include "generators/bridge_2d.hpp"

namespace railvsi {
namespace {

constexpr double kSpan = 20.0, kEI = 1.0e10;

std::shared_ptr<const StructureModel> simply_supported(double span_m) {
  Bridge2dOptions b;
  b.spans_m = {span_m};
  b.deck_EI_Nm2 = kEI;
  b.deck_mass_kg_per_m = 10000.0;
  b.damping_ratio = 0.01;
  return make_bridge_2d(b);
}

// Midspan deflection under a load P at distance a <= L/2 from a support.
double midspan_point(double P, double a, double L) { return P * a * (3 * L * L - 4 * a * a) / (48 * kEI); }
// Midspan deflection under q on [0, b] (b <= L/2): the integral of the above.
double midspan_partial_udl(double q, double b, double L) {
  return q * (1.5 * L * L * b * b - b * b * b * b) / (48 * kEI);
}

TEST(StaticInfluence, UnitLoadLineMatchesTheBeamFormula) {
  const auto s = simply_supported(kSpan);
  const StaticInfluence inf(*s);
  ASSERT_EQ(inf.num_points(), 1);  // span1_mid
  for (double a : {0.0, 1.3, 5.0, 7.77, 10.0}) {
    const double expect = midspan_point(1.0, a, kSpan);
    EXPECT_NEAR(inf.unit_deflection(0, a), expect, 1e-9 * midspan_point(1.0, kSpan / 2, kSpan)) << a;
    EXPECT_NEAR(inf.unit_deflection(0, kSpan - a), expect, 1e-9 * midspan_point(1.0, kSpan / 2, kSpan)) << a;
  }
  EXPECT_EQ(inf.unit_deflection(0, -1.0), 0.0);  // off the modelled track
}

TEST(StaticInfluence, TrainEnvelopeOfOneAxleIsTheMidspanLoad) {
  const auto s = simply_supported(kSpan);
  const StaticInfluence inf(*s);
  const StaticEnvelope e = inf.train_envelope(0, {{0.0, 170e3}});
  const double expect = 170e3 * kSpan * kSpan * kSpan / (48 * kEI);  // PL^3/48EI
  EXPECT_NEAR(e.max_deflection_m, expect, 1e-9 * expect);
  EXPECT_NEAR(e.first_axle_x_m, kSpan / 2, 1e-4);
}

TEST(StaticInfluence, TwoAxlesStraddleMidspan) {
  // Two equal loads 3 m apart on a simply supported beam: by symmetry and
  // concavity of the midspan influence line the maximum has them at
  // midspan -/+ 1.5 m.
  const auto s = simply_supported(kSpan);
  const StaticInfluence inf(*s);
  const StaticEnvelope e = inf.train_envelope(0, {{0.0, 100e3}, {3.0, 100e3}});
  const double expect = 2 * midspan_point(100e3, kSpan / 2 - 1.5, kSpan);
  EXPECT_NEAR(e.max_deflection_m, expect, 1e-9 * expect);
}

// A train far longer than the span: the envelopes sum only the axles that
// can stand on the rails at each position. The others add exact zeros, so
// the envelope is the plain sum over every axle to the bit, and the same
// axles given out of order (summed whole, in another order) agree to the
// rounding of that order.
TEST(StaticInfluence, ALongTrainOnAShortSpanSumsTheAxlesOnIt) {
  const auto s = simply_supported(12.0);
  const StaticInfluence inf(*s);
  std::vector<MovingForce> axles;
  for (int i = 0; i < 40; ++i) axles.push_back({3.0 * i + (i % 2 ? 0.4 : 0.0), 150e3 + 1e3 * (i % 7)});
  const StaticEnvelope e = inf.train_envelope(0, axles);
  double every_axle = 0.0;
  for (const MovingForce& a : axles) every_axle += a.load_N * inf.unit_deflection(0, e.first_axle_x_m - a.offset_m);
  EXPECT_GT(e.max_deflection_m, 0.0);
  EXPECT_EQ(e.max_deflection_m, std::abs(every_axle));
  // Above one 150 kN axle alone at midspan, PL^3/48EI: every axle on the span pushes it down.
  EXPECT_GT(e.max_deflection_m, midspan_point(150e3, 6.0, 12.0));

  // The axles reversed are summed whole in the other order. Measured: the
  // deflection and the moment equal to the bit, a reaction 1 ulp apart
  // (1.5e-16 relative): the reactions allow 4e-16.
  const std::vector<MovingForce> reversed(axles.rbegin(), axles.rend());
  const StaticEnvelope r = inf.train_envelope(0, reversed);
  EXPECT_EQ(r.max_deflection_m, e.max_deflection_m);
  const StaticSectionEnvelope sections = inf.section_envelope(axles), whole = inf.section_envelope(reversed);
  ASSERT_TRUE(sections.unavailable.empty()) << sections.unavailable;
  ASSERT_EQ(sections.max_abs_bending_moment_Nm.size(), 1u);
  ASSERT_TRUE(sections.max_abs_bending_moment_Nm[0] && whole.max_abs_bending_moment_Nm[0]);
  EXPECT_GT(*sections.max_abs_bending_moment_Nm[0], 0.0);
  EXPECT_EQ(*sections.max_abs_bending_moment_Nm[0], *whole.max_abs_bending_moment_Nm[0]);
  ASSERT_EQ(sections.max_reaction_N.size(), 2u);
  for (std::size_t i = 0; i < 2; ++i)
    EXPECT_NEAR(sections.max_reaction_N[i], whole.max_reaction_N[i], 4e-16 * sections.max_reaction_N[i]);
}

TEST(StaticInfluence, LoadModel71MidspanDeflectionMatchesTheHandCalculation) {
  // Point loads centred on midspan (at L/2 -/+ 0.8 and -/+ 2.4), q_vk on
  // [0, L/2 - 3.2] and [L/2 + 3.2, L].
  for (double L : {10.0, 20.0, 37.5}) {
    const auto s = simply_supported(L);
    const StaticInfluence inf(*s);
    const double expect = 2 * midspan_point(250e3, L / 2 - 0.8, L) + 2 * midspan_point(250e3, L / 2 - 2.4, L) +
                          2 * midspan_partial_udl(80e3, L / 2 - 3.2, L);
    const LoadModel71Result r = inf.lm71(0);
    // Measured: < 1e-9 relative (Gauss quadrature is exact on the cubic
    // pieces of the influence line).
    EXPECT_NEAR(r.max_deflection_m, expect, 1e-8 * expect) << "L = " << L;
    EXPECT_NEAR(r.first_point_load_x_m, L / 2 - 2.4, 1e-4) << "L = " << L;
  }
}

}  // namespace
}  // namespace railvsi
