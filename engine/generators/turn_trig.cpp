#include "generators/turn_trig.hpp"

#include <cmath>

namespace railvsi {
namespace {

constexpr double kQuarterTurnRad = 1.5707963267948966;  // pi/2, correctly rounded

// Taylor series on |x| <= pi/4 in x^2, highest power first; the first
// omitted terms (x^18/18!, x^19/19!) are below 3e-18.
constexpr double kCosSeries[] = {1.0 / 20922789888000.0, -1.0 / 87178291200.0, 1.0 / 479001600.0,
                                 -1.0 / 3628800.0,       1.0 / 40320.0,          -1.0 / 720.0,
                                 1.0 / 24.0,             -0.5,                   1.0};  // 1/16! ... 1
constexpr double kSinSeries[] = {1.0 / 355687428096000.0, -1.0 / 1307674368000.0, 1.0 / 6227020800.0,
                                 -1.0 / 39916800.0,       1.0 / 362880.0,          -1.0 / 5040.0,
                                 1.0 / 120.0,             -1.0 / 6.0,              1.0};  // 1/17! ... 1 (times x)

double horner(const double (&c)[9], double x2) {
  double p = c[0];
  for (int i = 1; i < 9; ++i) p = p * x2 + c[i];
  return p;
}

}  // namespace

CosSin cos_sin_turns(double t) {
  // In quarter turns u in [0, 4): u = q + f with q the nearest integer, so
  // that the angle f*pi/2 left for the series is within +-pi/4. For t >= 0
  // the fraction, the scaling by 4 and u - q are exact.
  const double u = 4.0 * (t - std::floor(t));
  const double q = std::floor(u + 0.5);
  const double x = (u - q) * kQuarterTurnRad;
  const double x2 = x * x;
  const double c = horner(kCosSeries, x2), s = horner(kSinSeries, x2) * x;
  switch (static_cast<int>(q) & 3) {
    case 0: return {c, s};
    case 1: return {-s, c};
    case 2: return {-c, -s};
    default: return {s, -c};
  }
}

}  // namespace railvsi
