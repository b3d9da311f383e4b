// Irregularity::at with a wheel's hint (the interval of its last call) gives
// the binary search's value bit for bit, whatever the hint.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "model/irregularity.hpp"

namespace railvsi {
namespace {

Irregularity uneven_profile() {
  std::vector<double> x, r;
  for (int i = 0; i < 200; ++i) {
    x.push_back(0.1 * i + 0.03 * std::sin(1.7 * i));  // uneven spacing, increasing
    r.push_back(1e-3 * std::cos(0.37 * i));
  }
  return Irregularity(x, r);
}

TEST(IrregularityHint, WheelMovingForwardGetsTheBinarySearchValue) {
  const Irregularity p = uneven_profile();
  std::size_t hint = 0;
  int checked = 0;
  for (double x = -0.5; x < 21.0; x += 0.0208333) {  // a wheel at 300 km/h, dt = 2.5e-4 s; past both ends
    const double want = p.at(x);
    EXPECT_EQ(p.at(x, hint), want) << x;  // the same operations: bit for bit
    ++checked;
  }
  EXPECT_GT(checked, 1000);
}

TEST(IrregularityHint, SamplesAndStaleHintsGetTheBinarySearchValue) {
  const Irregularity p = uneven_profile();
  const std::vector<double>& xs = p.x_m();
  for (std::size_t k = 0; k < xs.size(); ++k)
    for (std::size_t stale : {std::size_t{0}, k, k + 1, xs.size() - 2, xs.size() + 5}) {
      std::size_t hint = stale;
      EXPECT_EQ(p.at(xs[k], hint), p.at(xs[k])) << k << " " << stale;  // at a sample, and its left interval
      hint = stale;
      const double mid = k + 1 < xs.size() ? 0.5 * (xs[k] + xs[k + 1]) : xs[k];
      EXPECT_EQ(p.at(mid, hint), p.at(mid)) << k << " " << stale;
    }
}

}  // namespace
}  // namespace railvsi
