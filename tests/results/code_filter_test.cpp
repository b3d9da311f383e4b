// The deck acceleration filter of EN 1990 A2.4.4.2 (results/envelopes/code_filter.hpp).
// Expected gains come from the closed form of a Butterworth magnitude under
// the bilinear transform, written here independently of the filter code.
#include <gtest/gtest.h>

#include <array>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <vector>

#include "core/sampled_peak.hpp"
#include "envelopes/code_filter.hpp"
#include "../support/worst_of.hpp"

namespace railvsi {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kDt = 2.5e-4;  // 4 kHz sampling
constexpr double kCut = 30.0;

std::vector<double> sampled(double duration_s, double dt_s, auto f) {
  std::vector<double> x;
  for (std::size_t k = 0; k * dt_s <= duration_s + 1e-12; ++k) x.push_back(f(k * dt_s));
  return x;
}

// Amplitude of the f_hz component of x over samples [k0, k1): least squares
// fit of a sin + b cos.
double amplitude(const std::vector<double>& x, double dt_s, double f_hz, std::size_t k0, std::size_t k1) {
  double ss = 0, sc = 0, cc = 0, xs = 0, xc = 0;
  for (std::size_t k = k0; k < k1; ++k) {
    const double s = std::sin(2 * kPi * f_hz * k * dt_s), c = std::cos(2 * kPi * f_hz * k * dt_s);
    ss += s * s, sc += s * c, cc += c * c, xs += x[k] * s, xc += x[k] * c;
  }
  const double det = ss * cc - sc * sc;
  const double a = (xs * cc - xc * sc) / det, b = (xc * ss - xs * sc) / det;
  return std::hypot(a, b);
}

// Butterworth of n poles by the bilinear transform, both passes:
// |H(f)| = 1 / (1 + (tan(pi f dt) / tan(pi fc dt))^(2n)). With the design
// condition |H(f_cut)| = g this is
// 1 / (1 + (1/g - 1) (tan(pi f dt) / tan(pi f_cut dt))^(2n)).
double expected_gain(double f_hz, double dt_s, double cut_hz) {
  const double ratio = std::tan(kPi * f_hz * dt_s) / std::tan(kPi * cut_hz * dt_s);
  return 1.0 / (1.0 + (1.0 / 0.99 - 1.0) * std::pow(ratio, 16));
}

double gain(double f_hz) {
  const auto x = sampled(4.0, kDt, [&](double t) { return std::sin(2 * kPi * f_hz * t + 0.3); });
  const auto y = code_low_pass(x, kDt, kCut);
  return amplitude(y, kDt, f_hz, 4000, 12000) / amplitude(x, kDt, f_hz, 4000, 12000);
}

TEST(CodeCutoff, IsTheLargestOf30HzOneAndAHalfF0AndF3) {
  EXPECT_DOUBLE_EQ(code_cutoff_hz(4.0, 25.0), 30.0);
  EXPECT_DOUBLE_EQ(code_cutoff_hz(24.0, 31.0), 36.0);
  EXPECT_DOUBLE_EQ(code_cutoff_hz(8.0, 41.5), 41.5);
  EXPECT_DOUBLE_EQ(code_cutoff_hz(0.0, 0.0), 30.0);  // unknown frequencies
}

TEST(CodeFilter, KeepsTheAmplitudeOfA10HzSine) {
  const auto x = sampled(3.0, kDt, [](double t) { return 2.0 * std::sin(2 * kPi * 10.0 * t + 0.7); });
  const auto y = code_low_pass(x, kDt, kCut);
  ASSERT_EQ(y.size(), x.size());
  // Pointwise within 0.5 % of the amplitude away from the edges (0.2 s),
  // and within 2 % up to the edges (the odd reflection is not the sine).
  double inner = 0.0, all = 0.0;
  for (std::size_t k = 0; k < x.size(); ++k) {
    const double e = std::abs(y[k] - x[k]) / 2.0;
    all = railvsi::testing::worst_of(all, e);
    if (k * kDt > 0.2 && k * kDt < 2.8) inner = railvsi::testing::worst_of(inner, e);
  }
  EXPECT_LT(inner, 0.005);
  EXPECT_LT(all, 0.02);
  EXPECT_NEAR(amplitude(y, kDt, 10.0, 2000, 10000), 2.0, 2.0 * 0.005);
}

TEST(CodeFilter, RemovesA200HzComponent) {
  const auto x = sampled(3.0, kDt, [](double t) {
    return std::sin(2 * kPi * 10.0 * t + 0.7) + 0.5 * std::sin(2 * kPi * 200.0 * t + 0.1);
  });
  const auto y = code_low_pass(x, kDt, kCut);
  double residual = 0.0;
  for (std::size_t k = 0; k < x.size(); ++k)
    if (k * kDt > 0.2 && k * kDt < 2.8) residual = railvsi::testing::worst_of(residual, std::abs(y[k] - std::sin(2 * kPi * 10.0 * k * kDt + 0.7)));
  // What is left of the 200 Hz component (and the 10 Hz error) is < 1 % of its amplitude.
  EXPECT_LT(residual, 0.01 * 0.5);
  EXPECT_LT(amplitude(y, kDt, 200.0, 2000, 10000), 0.01 * 0.5);
}

TEST(CodeFilter, PassesAConstantUnchanged) {
  const std::vector<double> x(5000, -3.25);
  const auto y = code_low_pass(x, kDt, kCut);
  for (double v : y) EXPECT_NEAR(v, -3.25, 3.25e-11);  // round-off only
}

TEST(CodeFilter, GainMatchesTheButterworthDesignAtAndAboveTheCutoff) {
  // 99 % at the code frequency, 0.5 at the design frequency f_c, and the
  // closed form at 10 Hz, 1.5 and 2 times the cut-off.
  EXPECT_NEAR(gain(kCut), 0.99, 0.002);
  const double fc = code_filter_half_gain_hz(kDt, kCut);
  // In the analog limit f_c = f_cut (1/0.99 - 1)^(-1/16) = 1.3326 f_cut.
  EXPECT_NEAR(fc / kCut, std::pow(1.0 / 0.99 - 1.0, -1.0 / 16.0), 2e-3);
  EXPECT_NEAR(gain(fc), 0.5, 0.003);
  for (double f : {10.0, 45.0, 60.0}) EXPECT_NEAR(gain(f), expected_gain(f, kDt, kCut), 0.003) << f << " Hz";
  EXPECT_LT(gain(60.0), 0.002);
}

TEST(CodeFilter, IsZeroPhaseAPulseKeepsItsPeakTime) {
  // A smooth pulse centred at t = 1 s, 0.1 s wide: its peak stays on the same sample.
  const auto x = sampled(2.0, kDt, [](double t) { return std::exp(-0.5 * std::pow((t - 1.0) / 0.02, 2)); });
  const auto y = code_low_pass(x, kDt, kCut);
  const auto peak = [](const std::vector<double>& v) { return std::max_element(v.begin(), v.end()) - v.begin(); };
  EXPECT_EQ(peak(y), peak(x));
}

TEST(CodeFilter, SameInputGivesTheSameBits) {
  const auto x = sampled(1.0, kDt, [](double t) { return std::sin(2 * kPi * 7.0 * t) + 0.1 * std::cos(2 * kPi * 90.0 * t); });
  EXPECT_EQ(code_low_pass(x, kDt, kCut), code_low_pass(x, kDt, kCut));
}

TEST(CodeFilter, CutoffAboveNyquistLeavesTheSignalUnchanged) {
  const std::vector<double> x{0.0, 1.0, -1.0, 0.5};
  EXPECT_EQ(code_low_pass(x, 0.02, 30.0), x);  // Nyquist 25 Hz
}

TEST(CodeFilter, RejectsANonPositiveStepOrCutoff) {
  const std::vector<double> x{0.0, 1.0};
  EXPECT_THROW(code_low_pass(x, 0.0, 30.0), std::invalid_argument);
  EXPECT_THROW(code_low_pass(x, kDt, -1.0), std::invalid_argument);
}

// Signals filtered side by side (one lane each, as a batch of speeds
// filters its runs) give each the bits it has alone: different lengths, a
// signal too short to filter, a NaN that must come through, an idle lane.
TEST(CodeFilter, SignalsFilteredSideBySideGiveTheBitsOfEachAlone) {
  const double dt = 9.66e-4;
  const CodeFilter filter(dt, 30.0);
  const auto wave = [&](std::size_t n, double f_hz, double phase) {
    std::vector<double> x(n);
    for (std::size_t k = 0; k < n; ++k)
      x[k] = std::sin(2 * kPi * f_hz * dt * k + phase) + 0.3 * std::sin(2 * kPi * 70.0 * dt * k);
    return x;
  };
  std::vector<double> with_nan = wave(900, 9.0, 0.2);
  with_nan[450] = std::nan("");
  const std::vector<std::vector<std::vector<double>>> groups = {
      {wave(7001, 5.0, 0.1), wave(6500, 12.0, 1.0), wave(7189, 27.0, 2.0), wave(5000, 3.0, 0.4)},
      {wave(1, 5.0, 0.0), wave(2, 5.0, 0.5), with_nan},
      {wave(300, 20.0, 0.0)},
  };
  CodeFilter::LaneWorkspace workspaces;
  std::vector<double> alone_ws;
  for (const auto& group : groups) {
    std::vector<const std::vector<double>*> signals;
    for (const auto& g : group) signals.push_back(&g);
    for (const auto code : {LaneCode::kFastest, LaneCode::kPortable}) {
      double maxima[CodeFilter::kLanes];
      filter.max_abs_filtered(signals, maxima, workspaces, code);
      for (std::size_t l = 0; l < group.size(); ++l) {
        const double alone = filter.max_abs_filtered(group[l], alone_ws);
        if (std::isnan(alone)) EXPECT_TRUE(std::isnan(maxima[l])) << l;
        else EXPECT_EQ(maxima[l], alone) << "lane " << l << " of " << group.size()
                                         << (code == LaneCode::kFastest ? ", fastest code" : ", portable code");
      }
    }
  }
  EXPECT_TRUE(std::isnan(filter.max_abs_filtered(with_nan, alone_ws)));
}

// Values so small that b0 x is subnormal: 2 (b0 x) and (2 b0) x differ
// there, and the lanes and the single pass must still agree to the bit.
TEST(CodeFilter, SubnormalSignalsFilteredSideBySideGiveTheBitsOfEachAlone) {
  const CodeFilter filter(9.66e-4, 30.0);
  std::vector<double> tiny(2000);
  std::uint64_t state = 12345;
  for (double& v : tiny) {
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    v = (static_cast<double>(state >> 11) / 9007199254740992.0 - 0.5) * 1e-305;
  }
  CodeFilter::LaneWorkspace ws;
  std::vector<double> alone_ws;
  const double alone = filter.max_abs_filtered(tiny, alone_ws);
  ASSERT_GT(alone, 0.0);
  ASSERT_LT(alone, 1e-300);
  const std::vector<const std::vector<double>*> signals{&tiny, &tiny};
  for (const auto code : {LaneCode::kFastest, LaneCode::kPortable}) {
    double maxima[CodeFilter::kLanes];
    filter.max_abs_filtered(signals, maxima, ws, code);
    EXPECT_EQ(maxima[0], alone);
    EXPECT_EQ(maxima[1], alone);
  }
  // The filtered signal itself, as code_low_pass gives it, has the same (refined) maximum.
  const std::vector<double> low = code_low_pass(tiny, 9.66e-4, 30.0);
  EXPECT_EQ(refined_max_abs(low.data(), low.size()), alone);
}

}  // namespace
}  // namespace railvsi
