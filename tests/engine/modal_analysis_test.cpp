// Natural frequencies of generated bridges against closed forms, and the
// mode types named after their shapes (the solvers themselves:
// mode_solvers_test.cpp).
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "solver/modal_analysis.hpp"
#include "analysis/mode_classification.hpp"
#include "generators/bridge_2d.hpp"

namespace railvsi {
namespace {

constexpr double kPi = std::numbers::pi;

// f_n = n^2 pi / (2 L^2) sqrt(EI / m), written out here rather than taken
// from the generator's helper.
double ss_frequency_hz(int n, double L, double EI, double m) { return n * n * kPi / (2.0 * L * L) * std::sqrt(EI / m); }

Bridge2dOptions deck(std::vector<double> spans_m, double EI, double m) {
  Bridge2dOptions o;
  o.spans_m = std::move(spans_m);
  o.deck_EI_Nm2 = EI;
  o.deck_mass_kg_per_m = m;
  o.damping_ratio = 0.01;
  return o;
}

TEST(ModalAnalysis, SimplySupportedBeamAtTheDefaultMeshMatchesTheClosedForm) {
  const double L = 25.0, EI = 7.694e10, m = 15000.0;
  const auto s = make_bridge_2d(deck({L}, EI, m));  // default element length
  const ModalResult r = modal_analysis(*s);
  ASSERT_TRUE(r.status.ok()) << r.status.message();
  const double f1 = ss_frequency_hz(1, L, EI, m);
  EXPECT_NEAR(r.frequencies_hz[0] / f1, 1.0, 1e-3);
  EXPECT_NEAR(r.frequencies_hz[1] / (4.0 * f1), 1.0, 5e-3);
  EXPECT_NEAR(r.frequencies_hz[2] / (9.0 * f1), 1.0, 5e-3);
  for (int n = 1; n <= 3; ++n) {
    const ModeType t = classify_mode(*s, r.shapes.col(n - 1));
    EXPECT_TRUE(t.deck);
    EXPECT_NEAR(t.deck_energy_fraction, 1.0, 1e-12) << "no track: all energy in the deck";
    ASSERT_EQ(t.half_waves.size(), 1u);
    EXPECT_EQ(t.half_waves[0], n);
  }
  EXPECT_EQ(classify_mode(*s, r.shapes.col(0)).description, "deck bending, 1 half-wave in span 1");
  EXPECT_EQ(classify_mode(*s, r.shapes.col(1)).description, "deck bending, 2 half-waves in span 1");
}

TEST(ModalAnalysis, DeckGivenByItsFirstFrequencyHasThatFrequency) {
  Bridge2dOptions o = deck({18.0}, 0.0, 12000.0);
  o.deck_first_frequency_hz = 6.3;
  const auto s = make_bridge_2d(o);
  const ModalResult r = modal_analysis(*s);
  ASSERT_TRUE(r.status.ok()) << r.status.message();
  EXPECT_NEAR(r.frequencies_hz[0] / 6.3, 1.0, 1e-3);
  EXPECT_NEAR(s->info().first_frequency_hz, 6.3, 1e-9);
}

TEST(ModalAnalysis, ContinuousTwoSpanGirderMatchesSingleSpanAndClampedPinnedFrequencies) {
  // Equal spans: mode 1 bends each span as a simply supported one (the pier
  // is a point of inflection); mode 2 is symmetric, each span clamped at the
  // pier and pinned at its end: beta L = 3.92660 (Blevins, Formulas for
  // Natural Frequency and Mode Shape, Table 8-1, clamped-pinned).
  const double L = 20.0, EI = 4.0e10, m = 14000.0;
  Bridge2dOptions o = deck({L, L}, EI, m);
  o.continuous = true;
  const auto s = make_bridge_2d(o);
  const ModalResult r = modal_analysis(*s);
  ASSERT_TRUE(r.status.ok()) << r.status.message();
  EXPECT_NEAR(r.frequencies_hz[0] / ss_frequency_hz(1, L, EI, m), 1.0, 5e-3);
  const double beta_L = 3.92660231;
  const double f_clamped_pinned = beta_L * beta_L / (2.0 * kPi * L * L) * std::sqrt(EI / m);
  EXPECT_NEAR(r.frequencies_hz[1] / f_clamped_pinned, 1.0, 5e-3);
  for (int k = 0; k < 2; ++k)
    EXPECT_EQ(classify_mode(*s, r.shapes.col(k)).description, "deck bending, 1 half-wave in each of spans 1, 2");
}

TEST(ModalAnalysis, ViaductWithTrackHasDeckModesNearTheSpanFrequencyLoweredByTheTrackMass) {
  // Three simply supported spans under a ballasted track. At a few Hz the
  // track (rail and sleepers, springs tuned above 100 Hz) moves with the
  // deck as added mass: f ~ f_span sqrt(m / (m + m_rail + m_sleeper / s)).
  const double L = 25.0, EI = 7.124e10, m = 18000.0;
  Bridge2dOptions o = deck({L, L, L}, EI, m);
  o.track = TrackOptions{};
  const TrackOptions& t = *o.track;
  const auto s = make_bridge_2d(o);
  const ModalResult r = modal_analysis(*s);
  ASSERT_TRUE(r.status.ok()) << r.status.message();
  const double m_track = t.rail_mass_kg_per_m + t.sleeper_mass_kg / t.sleeper_spacing_m;
  const double expected = ss_frequency_hz(1, L, EI, m) * std::sqrt(m / (m + m_track));
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(r.frequencies_hz[k] / expected, 1.0, 5e-3) << "mode " << k + 1;
    const ModeType type = classify_mode(*s, r.shapes.col(k));
    EXPECT_TRUE(type.deck) << type.description;
    EXPECT_GT(type.deck_energy_fraction, 0.9);
    for (const int h : type.half_waves) EXPECT_LE(h, 1) << type.description;
  }
}

TEST(ModalAnalysis, ClusterOfEmbankmentTrackModesDoesNotStopConvergence) {
  // Nine deck modes (1, 2, 3 half-waves in three spans) below ~45 Hz, then
  // hundreds of nearly equal sleeper-on-ballast modes: the twelve lowest
  // must converge although the last ones lie inside that cluster. The
  // viaduct-ice3 example (approach 203.3 m): with a Lanczos basis of
  // 2 * 12 + 1 vectors this did not converge in 1000 iterations.
  Bridge2dOptions o = deck({25.0, 25.0, 25.0}, 7.124e10, 18000.0);
  o.track = TrackOptions{};
  o.track->approach_m = 203.3;
  const auto s = make_bridge_2d(o);
  ModalOptions options;
  options.modes = 12;
  const ModalResult r = modal_analysis(*s, options);
  ASSERT_TRUE(r.status.ok()) << r.status.message();
  ASSERT_EQ(r.frequencies_hz.size(), 12u);
  for (int k = 0; k < 9; ++k) {
    const ModeType type = classify_mode(*s, r.shapes.col(k));
    EXPECT_TRUE(type.deck) << "mode " << k + 1;
    for (const int h : type.half_waves) EXPECT_TRUE(h == 0 || h == k / 3 + 1) << "mode " << k + 1 << ": " << type.description;
  }
  for (int k = 9; k < 12; ++k) EXPECT_EQ(classify_mode(*s, r.shapes.col(k)).description, "track") << "mode " << k + 1;
  for (int k = 1; k < 12; ++k) EXPECT_GE(r.frequencies_hz[k], r.frequencies_hz[k - 1]);
}

TEST(ModalAnalysis, TrackModesAreNamedTrackWhenTheDeckIsFarStiffer) {
  // A deck at ~190 Hz: the lowest modes are the track's on its embankments.
  Bridge2dOptions o = deck({10.0}, 1.0e13, 10000.0);
  o.track = TrackOptions{};
  const auto s = make_bridge_2d(o);
  ModalOptions options;
  options.modes = 3;
  const ModalResult r = modal_analysis(*s, options);
  ASSERT_TRUE(r.status.ok()) << r.status.message();
  ASSERT_LT(r.frequencies_hz[0], 0.5 * ss_frequency_hz(1, 10.0, 1.0e13, 10000.0));
  const ModeType type = classify_mode(*s, r.shapes.col(0));
  EXPECT_FALSE(type.deck);
  EXPECT_LT(type.deck_energy_fraction, 0.5);
  EXPECT_EQ(type.description, "track");
}

}  // namespace
}  // namespace railvsi
