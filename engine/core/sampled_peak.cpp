#include "core/sampled_peak.hpp"

#include <cmath>
#include <limits>
#include <numbers>

namespace railvsi {

double refined_max_abs(const double* s, std::size_t n, std::size_t stride) {
  if (n == 0) return 0.0;
  // One pass over y = |s|: the largest sample and, at each local maximum,
  // the vertex of the parabola through it and its neighbours: y0, y1, y2
  // at -1, 0, 1 give y(x) = y1 + b x + a x^2 with a = (y0 + y2) / 2 - y1,
  // b = (y2 - y0) / 2, vertex y1 - b^2 / (4a) within half a step of the
  // middle sample when y1 >= y0, y2 and a < 0. The vertex is computed only
  // where it may exceed the running maximum m (b^2 >= 4 |a| (m - y1), with
  // a margin for rounding): rarely, so the loop has no division and one
  // branch that is almost never taken. Any vertex skipped is below m, so
  // the result is the maximum over all samples and vertices whatever the
  // stride or the order of the samples.
  double m = std::abs(s[0]);
  bool nan = std::isnan(s[0]);
  if (n == 1) return nan ? std::numeric_limits<double>::quiet_NaN() : m;
  double before = m, here = std::abs(s[stride]);
  for (std::size_t i = 1; i + 1 < n; ++i) {
    const double after = std::abs(s[(i + 1) * stride]);
    nan |= here != here;
    m = here > m ? here : m;
    const double a = 0.5 * (before + after) - here, b = 0.5 * (after - before);
    const bool peak = (here >= before) & (here >= after) & (a < 0.0);
    if (peak & (b * b >= -4.0 * a * (m - here) * (1.0 - 1e-9))) [[unlikely]] {
      const double vertex = here - b * b / (4.0 * a);
      m = vertex > m ? vertex : m;
    }
    before = here;
    here = after;
  }
  nan |= here != here;
  m = here > m ? here : m;
  return nan ? std::numeric_limits<double>::quiet_NaN() : m;
}

double sampled_peak_error(double samples_per_period) { return 1.0 - std::cos(std::numbers::pi / samples_per_period); }

double refined_peak_error(double samples_per_period) {
  const double half_step = std::numbers::pi / samples_per_period;
  const double s = std::sin(half_step);
  return 1.0 - std::cos(half_step) * (1.0 + 0.5 * s * s);
}

}  // namespace railvsi
