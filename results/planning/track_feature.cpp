#include "planning/track_feature.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include <fmt/format.h>

namespace railvsi {

std::string TrackFeature::describe() const {
  return fmt::format("a feature {:.3g} m long, {:.3g} mm peak to peak, at x = {:.2f} m", wavelength_m,
                     1e3 * height_m, x_m);
}

TrackFeature shortest_track_feature(const Irregularity& profile, double window_m, double min_height_m) {
  const std::vector<double>& x = profile.x_m();
  const std::vector<double>& r = profile.r_m();
  const std::size_t n = x.size();
  TrackFeature best;
  if (n < 3) return best;
  // Per interval i (x_i to x_i+1): its rise and midpoint; per interior
  // sample j: the change of slope there.
  std::vector<double> rise2(n - 1), mid(n - 1), kink2(n, 0.0);
  std::vector<double> slope(n - 1);
  for (std::size_t i = 0; i + 1 < n; ++i) {
    const double dr = r[i + 1] - r[i];
    rise2[i] = dr * dr;
    mid[i] = 0.5 * (x[i] + x[i + 1]);
    slope[i] = dr / (x[i + 1] - x[i]);
  }
  std::vector<double> curvature(n, 0.0);
  for (std::size_t j = 1; j + 1 < n; ++j) {
    // Below 1e-9 rad a change of slope is round-off (a linear profile).
    const double kink = std::abs(slope[j] - slope[j - 1]) > 1e-9 ? slope[j] - slope[j - 1] : 0.0;
    kink2[j] = kink * kink;
    curvature[j] = std::abs(kink) / std::min(x[j] - x[j - 1], x[j + 1] - x[j]);
  }
  // Windows centred on each interval's midpoint: intervals [lo, hi) with
  // their midpoints within window_m / 2, samples lo .. hi (their ends).
  std::size_t lo = 0, hi = 0;
  for (std::size_t i = 0; i + 1 < n; ++i) {
    while (mid[lo] < mid[i] - 0.5 * window_m) ++lo;
    if (hi < i + 1) hi = i + 1;
    while (hi < n - 1 && mid[hi] <= mid[i] + 0.5 * window_m) ++hi;
    double sum_rise = 0.0, sum_kink = 0.0, r_min = r[lo], r_max = r[lo], kappa = 0.0;
    for (std::size_t k = lo; k < hi; ++k) sum_rise += rise2[k];
    for (std::size_t k = lo; k <= hi; ++k) {
      sum_kink += kink2[k];
      kappa = std::max(kappa, curvature[k]);
      r_min = std::min(r_min, r[k]);
      r_max = std::max(r_max, r[k]);
    }
    // Only windows centred on the feature's bends (a kink of at least half
    // the window's largest): a window that clips the start of a dip would
    // see a shorter feature than the dip.
    double kink_max = 0.0;
    for (std::size_t k = lo; k <= hi; ++k) kink_max = std::max(kink_max, kink2[k]);
    const double kink_here = std::max(kink2[i], kink2[i + 1]);
    if (!(sum_kink > 0.0) || r_max - r_min < min_height_m || kink_here < 0.25 * kink_max) continue;
    const double lambda = 2.0 * std::numbers::pi * std::sqrt(sum_rise / sum_kink);
    if (best.wavelength_m == 0.0 || lambda < best.wavelength_m) best = {lambda, mid[i], r_max - r_min, kappa};
  }
  return best;
}

}  // namespace railvsi
