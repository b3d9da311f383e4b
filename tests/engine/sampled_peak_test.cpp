// The peak of a sampled signal, refined between its samples, against
// harmonics whose true peak is known.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include "core/sampled_peak.hpp"
#include "../support/worst_of.hpp"

namespace railvsi {
namespace {

constexpr double kPi = std::numbers::pi;

// A harmonic of amplitude `amplitude` sampled n times a period over three
// periods, its peaks `phase` of a step away from a sample.
std::vector<double> harmonic(double amplitude, int n, double phase) {
  std::vector<double> s;
  for (int i = 0; i <= 3 * n; ++i) s.push_back(amplitude * std::cos(2.0 * kPi * (i + phase) / n));
  return s;
}

TEST(SampledPeak, RefinedPeakOfAHarmonicIsLowByAtMostTheClosedFormBound) {
  // Even n: both lobes of |s| are half a step from a sample at once (for
  // odd n one of them is then sampled exactly).
  for (int n : {6, 8, 12, 24}) {
    double worst = 0.0, worst_sampled = 0.0;
    for (int k = 0; k <= 200; ++k) {
      const std::vector<double> s = harmonic(-2.5, n, 0.5 * k / 200.0);  // negative: |s| is what counts
      const double refined = refined_max_abs(s.data(), s.size());
      double sampled = 0.0;
      for (double v : s) sampled = railvsi::testing::worst_of(sampled, std::abs(v));
      EXPECT_LE(refined, 2.5 * (1.0 + 1e-14)) << "never above the true peak, n = " << n;
      EXPECT_GE(refined, sampled) << "never below the samples";
      worst = railvsi::testing::worst_of(worst, 1.0 - refined / 2.5);
      worst_sampled = railvsi::testing::worst_of(worst_sampled, 1.0 - sampled / 2.5);
    }
    // The bound is reached half a step from a sample (k = 200), within rounding.
    EXPECT_NEAR(worst, refined_peak_error(n), 1e-12) << n;
    EXPECT_NEAR(worst_sampled, sampled_peak_error(n), 1e-12) << n;
  }
  // 8 samples a period: 0.85 % against 7.6 % for the largest sample.
  EXPECT_NEAR(refined_peak_error(8), 0.008471, 1e-6);
  EXPECT_NEAR(sampled_peak_error(8), 0.076120, 1e-6);
}

TEST(SampledPeak, ParabolaThroughThreeSamplesGivesItsVertex) {
  // y = 4 - (x - 0.3)^2 at x = -1, 0, 1, 2: the vertex 4 at x = 0.3.
  std::vector<double> s;
  for (int x = -1; x <= 2; ++x) s.push_back(4.0 - (x - 0.3) * (x - 0.3));
  EXPECT_NEAR(refined_max_abs(s.data(), s.size()), 4.0, 1e-15);
}

TEST(SampledPeak, StrideSkipsTheOtherInterleavedSignals) {
  // Two interleaved signals: the second is ten times the first.
  const std::vector<double> a = harmonic(1.0, 8, 0.5);
  std::vector<double> both;
  for (double v : a) {
    both.push_back(v);
    both.push_back(10.0 * v);
  }
  EXPECT_EQ(refined_max_abs(both.data(), a.size(), 2), refined_max_abs(a.data(), a.size()));
}

TEST(SampledPeak, ReversedOrStridedSamplesGiveTheSameBits) {
  // The code filter refines its backward pass, which runs in reverse time.
  std::vector<double> s;
  for (int i = 0; i < 500; ++i) s.push_back(std::sin(0.37 * i) * (1.0 + 0.002 * i) - 0.3 * std::cos(2.9 * i));
  const std::vector<double> r(s.rbegin(), s.rend());
  EXPECT_EQ(refined_max_abs(s.data(), s.size()), refined_max_abs(r.data(), r.size()));
  // Contiguous samples go four at a time, strided ones one at a time: the same bits.
  std::vector<double> strided;
  for (double v : s) strided.insert(strided.end(), {v, 0.0, 0.0});
  EXPECT_EQ(refined_max_abs(s.data(), s.size()), refined_max_abs(strided.data(), s.size(), 3));
  // And the refinement did something here (the largest sample alone is lower).
  double sampled = 0.0;
  for (double v : s) sampled = railvsi::testing::worst_of(sampled, std::abs(v));
  EXPECT_GT(refined_max_abs(s.data(), s.size()), sampled);
}

// Every vertex, written out here without the skip of those below the
// largest sample: what refined_max_abs must equal.
double every_vertex(const std::vector<double>& s) {
  double m = 0.0;
  for (double v : s) m = railvsi::testing::worst_of(m, std::abs(v));
  for (std::size_t i = 1; i + 1 < s.size(); ++i) {
    const double y0 = std::abs(s[i - 1]), y1 = std::abs(s[i]), y2 = std::abs(s[i + 1]);
    const double a = 0.5 * (y0 + y2) - y1, b = 0.5 * (y2 - y0);
    if (y1 >= y0 && y1 >= y2 && a < 0.0) m = railvsi::testing::worst_of(m, y1 - b * b / (4.0 * a));
  }
  return m;
}

TEST(SampledPeak, PeakAtEveryIndexInEveryPathEqualsEveryVertex) {
  // Short signals (3 to 12 samples) whose peak sits at each index in turn,
  // half a step off: the ends of the four-at-a-time loop and of the scalar
  // loop, forward, reversed and strided, in AVX2 and in the baseline code.
  for (std::size_t n = 3; n <= 12; ++n)
    for (std::size_t peak = 0; peak < n; ++peak) {
      std::vector<double> s;
      for (std::size_t i = 0; i < n; ++i) s.push_back(std::cos(0.7 * (static_cast<double>(i) - peak - 0.5)));
      const double expected = every_vertex(s);
      const std::vector<double> r(s.rbegin(), s.rend());
      std::vector<double> strided;
      for (double v : s) strided.insert(strided.end(), {v, 9.0});  // the other signal is larger: never read
      for (const auto code : {LaneCode::kFastest, LaneCode::kPortable}) {
        EXPECT_EQ(refined_max_abs(s.data(), n, 1, code), expected) << n << " " << peak;
        EXPECT_EQ(refined_max_abs(r.data(), n, 1, code), expected) << n << " " << peak;
        EXPECT_EQ(refined_max_abs(strided.data(), n, 2, code), expected) << n << " " << peak;
      }
      // An interior peak half a step off is raised above its samples.
      if (peak >= 1 && peak + 2 < n) {
        EXPECT_GT(expected, std::abs(s[peak])) << n << " " << peak;
      }
    }
}

TEST(SampledPeak, HugeSamplesDoNotOverflowTheVertex) {
  // b^2 would overflow: the peak is finite, 1.125e200 (the parabola through
  // 1e200, 1e200, 0 at -1, 0, 1 peaks at x = -1/2).
  const std::vector<double> s{-1e200, 1e200, 0.0};
  EXPECT_DOUBLE_EQ(refined_max_abs(s.data(), s.size()), 1.125e200);
}

TEST(SampledPeak, EndsPlateausAndNaNAreHandled) {
  EXPECT_EQ(refined_max_abs(nullptr, 0), 0.0);
  const std::vector<double> rising{0.0, 1.0, 2.0, 3.0};  // the peak is the last sample: no parabola past it
  EXPECT_EQ(refined_max_abs(rising.data(), rising.size()), 3.0);
  const std::vector<double> flat{1.0, 1.0, 1.0};  // a plateau: the samples themselves
  EXPECT_EQ(refined_max_abs(flat.data(), flat.size()), 1.0);
  const std::vector<double> nan{0.0, std::numeric_limits<double>::quiet_NaN(), 1.0};
  EXPECT_TRUE(std::isnan(refined_max_abs(nan.data(), nan.size())));
}

}  // namespace
}  // namespace railvsi
