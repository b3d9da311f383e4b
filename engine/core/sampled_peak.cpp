#include "core/sampled_peak.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>


namespace railvsi {

double refined_max_abs(const double* s, std::size_t n, std::size_t stride, LaneCode code) {
  // The largest sample in four independent maxima (no chain of
  // dependent comparisons), then the vertices.
  double m[4] = {0.0, 0.0, 0.0, 0.0};
  bool nan = false;
  std::size_t i = 0;
  for (; i + 4 <= n; i += 4)
    for (std::size_t k = 0; k < 4; ++k) {
      const double v = std::abs(s[(i + k) * stride]);
      nan |= v != v;
      m[k] = v > m[k] ? v : m[k];
    }
  for (; i < n; ++i) {
    const double v = std::abs(s[i * stride]);
    nan |= v != v;
    m[0] = v > m[0] ? v : m[0];
  }
  if (nan) return std::numeric_limits<double>::quiet_NaN();
  return refine_max_abs(s, n, stride, std::max(std::max(m[0], m[1]), std::max(m[2], m[3])), code);
}

namespace {

// Whether the vertex at the middle of y0, y1, y2 (each |s|) may exceed the
// largest sample m (the same expression, element by element, in the
// vector loop below); the vertex itself.
[[gnu::always_inline]] inline bool may_exceed(double y0, double y1, double y2, double m) {
  const double a = 0.5 * (y0 + y2) - y1, b = 0.5 * (y2 - y0);
  return (y1 >= y0) & (y1 >= y2) & (a < 0.0) & (b * b >= -4.0 * a * (m - y1) * (1.0 - 1e-9));
}
[[gnu::always_inline]] inline double vertex(double y0, double y1, double y2) {
  const double a = 0.5 * (y0 + y2) - y1, b = 0.5 * (y2 - y0);
  // Samples above about 1e154 would overflow b^2 (finite samples, an
  // infinite peak): divide first there.
  const double b2 = b * b;
  return b2 <= std::numeric_limits<double>::max() ? y1 - b2 / (4.0 * a) : y1 - b * (b / (4.0 * a));
}

using Four = double __attribute__((vector_size(4 * sizeof(double))));
using FourInBuffer = double __attribute__((vector_size(4 * sizeof(double)), aligned(alignof(double)), may_alias));

// Samples 1 .. n - 2 of contiguous s (stride 1), four at a time; returns
// the first sample not yet looked at. No vector crosses a call. Compiled
// for the baseline processor and for AVX2 (four doubles one register; no
// FMA, so the same bits).
[[gnu::always_inline]] inline std::size_t refine_contiguous(const double* s, std::size_t n, double m, double& best) {
  std::size_t i = 1;
  for (; i + 4 < n; i += 4) {
    Four y0 = *reinterpret_cast<const FourInBuffer*>(s + i - 1);
    Four y1 = *reinterpret_cast<const FourInBuffer*>(s + i);
    Four y2 = *reinterpret_cast<const FourInBuffer*>(s + i + 1);
    y0 = y0 < 0.0 ? -y0 : y0;
    y1 = y1 < 0.0 ? -y1 : y1;
    y2 = y2 < 0.0 ? -y2 : y2;
    const Four a = 0.5 * (y0 + y2) - y1, b = 0.5 * (y2 - y0);
    const auto mask = (y1 >= y0) & (y1 >= y2) & (a < 0.0) & (b * b >= -4.0 * a * (m - y1) * (1.0 - 1e-9));
    if ((mask[0] | mask[1] | mask[2] | mask[3]) != 0) [[unlikely]]
      for (std::size_t k = i; k < i + 4; ++k) {
        const double z0 = std::abs(s[k - 1]), z1 = std::abs(s[k]), z2 = std::abs(s[k + 1]);
        if (may_exceed(z0, z1, z2, m)) best = std::max(best, vertex(z0, z1, z2));
      }
  }
  return i;
}
std::size_t refine_contiguous_baseline(const double* s, std::size_t n, double m, double& best) {
  return refine_contiguous(s, n, m, best);
}
[[gnu::target("avx2")]] std::size_t refine_contiguous_avx2(const double* s, std::size_t n, double m, double& best) {
  return refine_contiguous(s, n, m, best);
}

}  // namespace

double refine_max_abs(const double* s, std::size_t n, std::size_t stride, double max_abs_sample, LaneCode code) {
  if (n < 3 || std::isnan(max_abs_sample)) return max_abs_sample;
  // Over y = |s|, at each local maximum, the vertex of the parabola through
  // it and its neighbours: y0, y1, y2 at -1, 0, 1 give y(x) = y1 + b x +
  // a x^2 with a = (y0 + y2) / 2 - y1, b = (y2 - y0) / 2, vertex y1 - b^2 /
  // (4a) within half a step of the middle sample when y1 >= y0, y2 and
  // a < 0. It is computed only where it may exceed the largest sample M
  // (b^2 >= 4 |a| (M - y1), with a margin for rounding): rarely, so the
  // loop has no division, no chain from one sample to the next and one
  // branch that is almost never taken. Any vertex skipped is below M, so
  // the result is the maximum over all samples and vertices whatever the
  // stride or the order of the samples.
  const double m = max_abs_sample;
  double best = m;
  std::size_t first = 1;
  if (stride == 1)
    first = use_avx2(code) ? refine_contiguous_avx2(s, n, m, best) : refine_contiguous_baseline(s, n, m, best);
  for (std::size_t i = first; i + 1 < n; ++i) {
    const double y0 = std::abs(s[(i - 1) * stride]), y1 = std::abs(s[i * stride]), y2 = std::abs(s[(i + 1) * stride]);
    if (may_exceed(y0, y1, y2, m)) [[unlikely]]
      best = std::max(best, vertex(y0, y1, y2));
  }
  return best;
}

double sampled_peak_error(double samples_per_period) { return 1.0 - std::cos(std::numbers::pi / samples_per_period); }

double refined_peak_error(double samples_per_period) {
  const double half_step = std::numbers::pi / samples_per_period;
  const double s = std::sin(half_step);
  return 1.0 - std::cos(half_step) * (1.0 + 0.5 * s * s);
}

}  // namespace railvsi
