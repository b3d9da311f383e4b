#pragma once
// The running maximum of an error that a missing value cannot pass:
// std::max(worst, NaN) keeps worst, so a NaN (or an absent value read as
// NaN) vanished from `worst = std::max(worst, err)` and the test passed.
// worst_of returns NaN from then on, and every EXPECT_LE / EXPECT_LT /
// EXPECT_NEAR on it fails.
#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

namespace railvsi::testing {

inline double worst_of(double worst, double x) {
  if (std::isnan(worst) || std::isnan(x)) return std::numeric_limits<double>::quiet_NaN();
  return std::max(worst, x);
}

// An optional value as a number: NaN when absent, so that it fails every comparison.
inline double value_or_nan(const std::optional<double>& v) {
  return v ? *v : std::numeric_limits<double>::quiet_NaN();
}

}  // namespace railvsi::testing
