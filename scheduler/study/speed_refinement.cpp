#include "study/speed_refinement.hpp"

#include <algorithm>
#include <cmath>
#include <set>

namespace railvsi::scheduler {

std::vector<double> refinement_speeds(std::vector<SpeedValue> curve, const RefineOptions& options) {
  std::sort(curve.begin(), curve.end(), [](const SpeedValue& a, const SpeedValue& b) { return a.speed_kmh < b.speed_kmh; });
  double largest = 0.0;
  for (const SpeedValue& c : curve)
    if (c.value) largest = std::max(largest, *c.value);
  std::set<double> added;
  const auto midpoint = [&](double a, double b) {
    if (b - a <= options.tolerance_kmh) return;
    // Rounded to 1e-6 km/h: the job ids do not depend on the last bits.
    added.insert(std::round((a + b) / 2.0 * 1e6) / 1e6);
  };
  for (std::size_t k = 0; k < curve.size(); ++k) {
    if (!curve[k].value || *curve[k].value < options.min_fraction_of_max * largest || !(largest > 0.0)) continue;
    const bool has_left = k > 0, has_right = k + 1 < curve.size();
    if ((has_left && !curve[k - 1].value) || (has_right && !curve[k + 1].value)) continue;
    // A local maximum: not below either neighbour.
    if ((has_left && *curve[k - 1].value > *curve[k].value) || (has_right && *curve[k + 1].value > *curve[k].value))
      continue;
    if (has_left) midpoint(curve[k - 1].speed_kmh, curve[k].speed_kmh);
    if (has_right) midpoint(curve[k].speed_kmh, curve[k + 1].speed_kmh);
  }
  return {added.begin(), added.end()};
}

}  // namespace railvsi::scheduler
