// The geometry a rigid wheel follows: the x-derivatives of the Hermite rail
// row and the C2 spline of the irregularity profile.
#include <cmath>
#include <numbers>
#include <vector>

#include <gtest/gtest.h>

#include "model/irregularity.hpp"
#include "model/rail_line.hpp"

namespace railvsi {
namespace {

TEST(RigidPathGeometry, HermiteSlopesAndCurvaturesAreTheDerivativesOfTheWeights) {
  const double h = 0.6, e = 1e-5;
  for (double xi : {0.0, 0.13, 0.5, 0.77, 1.0}) {
    const double a = std::max(0.0, xi - e / h), b = std::min(1.0, xi + e / h);
    const auto w0 = hermite_weights(a, h), w1 = hermite_weights(b, h);
    const auto s0 = hermite_slopes(a, h), s1 = hermite_slopes(b, h);
    // Differences over [a, b] are central about its midpoint: error
    // O(e^2) ~ 1e-10, round-off ~ 1e-16 / 1e-5 = 1e-11.
    const double m = 0.5 * (a + b);
    const auto s = hermite_slopes(m, h), c = hermite_curvatures(m, h);
    for (int k = 0; k < 4; ++k) {
      EXPECT_NEAR(s[k], (w1[k] - w0[k]) / ((b - a) * h), 1e-6) << "xi " << xi << " k " << k;
      EXPECT_NEAR(c[k], (s1[k] - s0[k]) / ((b - a) * h), 1e-5 * std::max(1.0, std::abs(c[k]))) << "xi " << xi << " k " << k;
    }
  }
}

TEST(RigidPathGeometry, LocatedRowCarriesTheDerivativeWeights) {
  const RailLine line = RailLine::from_nodes("rail", {0.0, 0.6, 1.2}, {0, 2, 4}, {1, 3, 5});
  const auto row = line.locate(0.9);
  ASSERT_TRUE(row);
  const auto s = hermite_slopes(0.5, 0.6), c = hermite_curvatures(0.5, 0.6);
  for (int k = 0; k < 4; ++k) {
    EXPECT_NEAR(row->slope[k], s[k], 1e-12);
    EXPECT_NEAR(row->curvature[k], c[k], 1e-12);
  }
}

TEST(RigidPathGeometry, ProfileSplineFollowsASmoothProfileAndItsDerivatives) {
  // r = A sin(2 pi x / L), L = 3 m (the shortest wavelength of the German
  // spectra), sampled every 0.05 m. A cubic spline's errors are O(h^4),
  // O(h^3), O(h^2) for r and its two derivatives (k h = 0.105); measured
  // away from the natural ends, relative: 3.1e-7, 9.2e-6, 8.9e-4.
  const double A = 1e-3, L = 3.0, k = 2.0 * std::numbers::pi / L;
  std::vector<double> x, r;
  for (int i = 0; i <= 400; ++i) {
    x.push_back(0.05 * i);
    r.push_back(A * std::sin(k * x.back()));
  }
  const Irregularity profile(x, r, "sine");
  for (double xi = 3.0; xi <= 17.0; xi += 0.0371) {
    const ProfilePoint p = profile.smooth_at(xi);
    EXPECT_NEAR(p.r_m, A * std::sin(k * xi), 1e-6 * A);
    EXPECT_NEAR(p.slope, A * k * std::cos(k * xi), 3e-5 * A * k);
    EXPECT_NEAR(p.curvature_per_m, -A * k * k * std::sin(k * xi), 2e-3 * A * k * k);
  }
  // Interpolating: the samples themselves, and zero outside the profile.
  EXPECT_NEAR(profile.smooth_at(x[57]).r_m, r[57], 1e-15);
  EXPECT_EQ(profile.smooth_at(-1.0).r_m, 0.0);
  EXPECT_EQ(profile.smooth_at(21.0).curvature_per_m, 0.0);
}

}  // namespace
}  // namespace railvsi
