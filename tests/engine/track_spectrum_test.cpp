// Random track profiles from the spectra of track_spectrum.hpp: variance
// against closed-form integrals of the spectra, the published ordering of
// the track qualities, and reproducibility checked against the published
// SplitMix64 reference rather than against the code under test.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <map>
#include <string>
#include <numbers>
#include <vector>

#include <gtest/gtest.h>

#include "core/input_error.hpp"
#include "core/split_mix64.hpp"
#include "generators/spectrum_profile.hpp"
#include "generators/track_spectrum.hpp"
#include "generators/turn_trig.hpp"

namespace railvsi {
namespace {

constexpr double kPi = std::numbers::pi;

// SplitMix64 exactly as in the reference code (prng.di.unimi.it/splitmix64.c),
// written out again here so that the test does not trust the engine's copy.
std::uint64_t reference_splitmix64(std::uint64_t& x) {
  std::uint64_t z = (x += UINT64_C(0x9E3779B97F4A7C15));
  z = (z ^ (z >> 30)) * UINT64_C(0xBF58476D1CE4E5B9);
  z = (z ^ (z >> 27)) * UINT64_C(0x94D049BB133111EB);
  return z ^ (z >> 31);
}

// Integral of the one-sided PSD over [w1, w2] in closed form (partial
// fractions of the spectrum formulas), in m^2.
double german_band_variance(double A_v, double w1, double w2) {
  const double c = 0.8246, r = 0.0206;
  const auto F = [&](double w) { return A_v * c * c / (c * c - r * r) * (std::atan(w / r) / r - std::atan(w / c) / c); };
  return F(w2) - F(w1);
}
double fra_band_variance(double A_v_cm2, double w1, double w2) {
  const double c = 0.8245, k = 0.25;
  const auto F = [&](double w) { return 1e-4 * k * A_v_cm2 * (-1.0 / w - std::atan(w / c) / c); };
  return F(w2) - F(w1);
}

struct NamedSpectrum {
  const char* name;
  bool german;
  double A_v;  // as in the cited spectra
};
const NamedSpectrum kDataMd[] = {
    {"german-low", true, 4.032e-7}, {"german-high", true, 1.080e-6}, {"fra-1", false, 1.2107},
    {"fra-2", false, 1.0181},       {"fra-3", false, 0.6816},        {"fra-4", false, 0.5376},
    {"fra-5", false, 0.2095},       {"fra-6", false, 0.0339},
};

const TrackSpectrum& spectrum(const char* name) {
  const TrackSpectrum* s = find_track_spectrum(name);
  if (!s) throw std::runtime_error(std::string("no spectrum ") + name);
  return *s;
}

double sample_variance(const std::vector<double>& r) {
  double mean = 0.0;
  for (double v : r) mean += v;
  mean /= static_cast<double>(r.size());
  double sum = 0.0;
  for (double v : r) sum += (v - mean) * (v - mean);
  return sum / static_cast<double>(r.size() - 1);
}

// Mean over seeds 1..20 of the sample variance of 5 km of profile in the
// default band (3-70 m), sampled every 0.5 m (6 samples per shortest wave).
double mean_variance_over_seeds(const TrackSpectrum& s) {
  double sum = 0.0;
  const int seeds = 20;
  for (int seed = 1; seed <= seeds; ++seed) {
    SpectrumSampling sampling;
    sampling.seed = static_cast<std::uint64_t>(seed);
    sampling.sample_spacing_m = 0.5;
    sum += sample_variance(spectrum_profile(s, sampling, {0.0, 5000.0}).r_m());
  }
  return sum / seeds;
}

// The variances of every spectrum, measured once for the tests of the suite.
class SpectrumVariance : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    for (const NamedSpectrum& n : kDataMd) measured_[n.name] = mean_variance_over_seeds(spectrum(n.name));
  }
  static std::map<std::string, double> measured_;
};
std::map<std::string, double> SpectrumVariance::measured_;

TEST(SplitMix64, MatchesThePublishedReferenceSequence) {
  // Rosetta Code "Pseudo-random numbers/Splitmix64", seed 1234567.
  SplitMix64 rng(1234567);
  for (std::uint64_t expected : {UINT64_C(6457827717110365317), UINT64_C(3203168211198807973),
                                 UINT64_C(9817491932198370423), UINT64_C(4593380528125082431),
                                 UINT64_C(16408922859458223821)})
    EXPECT_EQ(rng.next(), expected);
}

TEST(SplitMix64, FirstOutputsForSeed7AreThoseOfTheReferenceAlgorithm) {
  SplitMix64 rng(7), unit_rng(7);
  std::uint64_t state = 7;
  for (int i = 0; i < 5; ++i) {
    const std::uint64_t expected = reference_splitmix64(state);
    EXPECT_EQ(rng.next(), expected) << "output " << i;
    // The top 53 bits over 2^53, an exact value.
    EXPECT_EQ(unit_rng.next_unit(), std::ldexp(static_cast<double>(expected >> 11), -53)) << "output " << i;
  }
}

TEST(TurnTrig, AgreesWithTheLibraryCosineAndSine) {
  double worst = 0.0;
  for (int i = -20000; i <= 20000; ++i) {
    const double t = i * 0.000731 + 0.1 * std::sin(i);  // irregular angles, negative and many turns
    const CosSin z = cos_sin_turns(t);
    worst = std::max({worst, std::abs(z.cos - std::cos(2.0 * kPi * t)), std::abs(z.sin - std::sin(2.0 * kPi * t))});
  }
  // std::cos(2 pi t) itself carries the rounding of 2 pi t (|t| up to 15 turns).
  EXPECT_LT(worst, 2e-14);
  for (double t : {0.0, 0.25, 0.5, 0.75, 1.0, -0.5}) EXPECT_EQ(std::abs(cos_sin_turns(t).cos), t == 0.25 || t == 0.75 ? 0.0 : 1.0) << t;
}

TEST(TrackSpectrum, HasTheSpectraOfTheReferenceData) {
  for (const NamedSpectrum& n : kDataMd) {
    SCOPED_TRACE(n.name);
    const TrackSpectrum& s = spectrum(n.name);
    EXPECT_EQ(s.A_v, n.A_v);
    // The PSD at one frequency, from the spectrum formula written out here.
    const double w = 0.5;
    const double expected = n.german ? n.A_v * 0.8246 * 0.8246 / ((w * w + 0.0206 * 0.0206) * (w * w + 0.8246 * 0.8246))
                                     : 1e-4 * 0.25 * n.A_v * 0.8245 * 0.8245 / (w * w * (w * w + 0.8245 * 0.8245));
    EXPECT_NEAR(s.psd(w), expected, 1e-12 * expected);
  }
  EXPECT_EQ(find_track_spectrum("german-medium"), nullptr);
}

TEST_F(SpectrumVariance, SampleVarianceAveragedOverSeedsIsTheIntegralOfTheSpectrumOverTheBand) {
  const double w1 = 2.0 * kPi / 70.0, w2 = 2.0 * kPi / 3.0;
  for (const NamedSpectrum& n : kDataMd) {
    SCOPED_TRACE(n.name);
    const double expected = n.german ? german_band_variance(n.A_v, w1, w2) : fra_band_variance(n.A_v, w1, w2);
    const double measured = measured_.at(n.name);
    RecordProperty(std::string(n.name) + "_variance_m2", std::to_string(measured) + " vs " + std::to_string(expected));
    std::printf("%-12s variance %.5e m^2, integral %.5e m^2, ratio %.4f\n", n.name, measured, expected,
                measured / expected);
    EXPECT_NEAR(measured / expected, 1.0, 0.05);
  }
}

TEST_F(SpectrumVariance, BetterTrackClassesHaveSmallerVariance) {
  EXPECT_LT(measured_.at("german-low"), measured_.at("german-high"));
  for (int c = 2; c <= 6; ++c)
    EXPECT_LT(measured_.at("fra-" + std::to_string(c)), measured_.at("fra-" + std::to_string(c - 1))) << "class " << c;
}

TEST(SpectrumProfile, IsTheSumOfCosinesWithReferencePhases) {
  // r(x) = sum_k sqrt(2 G(W_k) dW) cos(W_k x + 2 pi u_k), u_k the k-th
  // reference SplitMix64 draw, W_k the midpoints of N equal parts of the band;
  // evaluated here with std::cos at the stored samples.
  const TrackSpectrum& s = spectrum("german-high");
  SpectrumSampling sampling;
  sampling.seed = 7;
  sampling.components = 300;
  const Irregularity profile = spectrum_profile(s, sampling, {-40.0, 60.0});
  std::uint64_t state = 7;
  std::vector<double> phase(300);
  for (double& p : phase) p = 2.0 * kPi * std::ldexp(static_cast<double>(reference_splitmix64(state) >> 11), -53);
  const double w1 = 2.0 * kPi / 70.0, dw = (2.0 * kPi / 3.0 - w1) / 300;
  const double sigma = std::sqrt(german_band_variance(1.080e-6, w1, w1 + 300 * dw));
  for (std::size_t i = 0; i < profile.x_m().size(); i += 97) {
    const double x = profile.x_m()[i];
    double r = 0.0;
    for (int k = 0; k < 300; ++k) {
      const double w = w1 + (k + 0.5) * dw;
      r += std::sqrt(2.0 * s.psd(w) * dw) * std::cos(w * x + phase[static_cast<std::size_t>(k)]);
    }
    EXPECT_NEAR(profile.r_m()[i], r, 1e-10 * sigma) << "x = " << x;
  }
}

TEST(SpectrumProfile, SameSeedGivesBitIdenticalProfilesAndOtherSeedsDiffer) {
  const TrackSpectrum& s = spectrum("fra-4");
  SpectrumSampling a;
  a.seed = 7;
  const Irregularity p1 = spectrum_profile(s, a, {-150.0, 400.0});
  const Irregularity p2 = spectrum_profile(s, a, {-150.0, 400.0});
  ASSERT_EQ(p1.r_m().size(), p2.r_m().size());
  EXPECT_EQ(std::memcmp(p1.r_m().data(), p2.r_m().data(), p1.r_m().size() * sizeof(double)), 0);
  EXPECT_EQ(std::memcmp(p1.x_m().data(), p2.x_m().data(), p1.x_m().size() * sizeof(double)), 0);

  SpectrumSampling b = a;
  b.seed = 8;
  const Irregularity p3 = spectrum_profile(s, b, {-150.0, 400.0});
  std::size_t equal = 0;
  for (std::size_t i = 0; i < p1.r_m().size(); ++i) equal += p1.r_m()[i] == p3.r_m()[i];
  EXPECT_LT(equal, p1.r_m().size() / 100);
}

TEST(SpectrumProfile, OverlappingTracksHaveTheSameProfileBitForBit) {
  const TrackSpectrum& s = spectrum("german-low");
  SpectrumSampling a;
  a.seed = 3;
  const Irregularity wide = spectrum_profile(s, a, {-500.0, 500.0});
  const Irregularity narrow = spectrum_profile(s, a, {37.3, 81.9});
  std::size_t compared = 0;
  for (std::size_t i = 0; i < narrow.x_m().size(); ++i) {
    const double x = narrow.x_m()[i];
    const auto it = std::find(wide.x_m().begin(), wide.x_m().end(), x);
    ASSERT_NE(it, wide.x_m().end()) << x;
    EXPECT_EQ(wide.r_m()[static_cast<std::size_t>(it - wide.x_m().begin())], narrow.r_m()[i]) << x;
    ++compared;
  }
  EXPECT_GT(compared, 440u);
  EXPECT_LE(narrow.x_m().front(), 37.3);
  EXPECT_GE(narrow.x_m().back(), 81.9);
}

TEST(SpectrumProfile, SourceRecordsSpectrumSeedBandAndComponents) {
  SpectrumSampling a;
  a.seed = 7;
  const std::string source = spectrum_profile(spectrum("german-high"), a, {0.0, 10.0}).source();
  for (const char* part : {"german-high", "A_v = 1.080e-06 m*rad", "seed 7", "3-70 m", "2000 components", "0.1 m"})
    EXPECT_NE(source.find(part), std::string::npos) << part << " in " << source;
}

std::string error_path(const TrackSpectrum& s, const SpectrumSampling& sampling) {
  try {
    spectrum_profile(s, sampling, {0.0, 100.0});
  } catch (const InputError& e) {
    return e.json_path();
  }
  return "(accepted)";
}

TEST(SpectrumProfile, RejectsEmptyBandsBandsOutsideValidityAndAliasingSpacings) {
  SpectrumSampling empty_band;
  empty_band.seed = 1;
  empty_band.wavelength_min_m = 70.0;
  EXPECT_EQ(error_path(spectrum("german-high"), empty_band), "/wavelength_min_m");
  SpectrumSampling short_waves;
  short_waves.wavelength_min_m = 1.0;  // FRA: 1.524 m at least
  EXPECT_EQ(error_path(spectrum("fra-3"), short_waves), "/wavelength_min_m");
  EXPECT_EQ(error_path(spectrum("german-high"), short_waves), "(accepted)");
  SpectrumSampling long_waves;
  long_waves.wavelength_max_m = 400.0;  // FRA: 304.8 m at most
  EXPECT_EQ(error_path(spectrum("fra-3"), long_waves), "/wavelength_max_m");
  SpectrumSampling coarse;
  coarse.sample_spacing_m = 2.0;  // above half the 3 m shortest wave
  EXPECT_EQ(error_path(spectrum("fra-3"), coarse), "/sample_spacing_m");
}

}  // namespace
}  // namespace railvsi
