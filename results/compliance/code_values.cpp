#include "compliance/code_values.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace railvsi {

CodeValue deck_acceleration_limit_ballasted_mps2() { return {3.5, "EN 1990 A2.4.4.2.1(4)P", true}; }
CodeValue deck_acceleration_limit_direct_fastening_mps2() { return {5.0, "EN 1990 A2.4.4.2.1(4)P", true}; }

double dynamic_factor_phi2(double L) {
  return std::clamp(1.44 / (std::sqrt(L) - 0.2) + 0.82, 1.0, 1.67);
}

double dynamic_factor_phi3(double L) {
  return std::clamp(2.16 / (std::sqrt(L) - 0.2) + 0.73, 1.0, 2.0);
}

double determinant_length_m(const std::vector<double>& spans_m, bool continuous) {
  if (spans_m.empty()) return 0.0;
  const double longest = *std::max_element(spans_m.begin(), spans_m.end());
  if (!continuous || spans_m.size() == 1) return longest;
  const double mean = std::accumulate(spans_m.begin(), spans_m.end(), 0.0) / static_cast<double>(spans_m.size());
  const double k = spans_m.size() == 2 ? 1.2 : spans_m.size() == 3 ? 1.3 : spans_m.size() == 4 ? 1.4 : 1.5;
  return std::max(k * mean, longest);
}

double phi_double_prime(double L, double f0_hz, double speed_mps) {
  const double a = std::min(speed_mps / 22.0, 1.0);
  const double v = a / 100.0 *
                   (56.0 * std::exp(-(L / 10.0) * (L / 10.0)) +
                    50.0 * (f0_hz * L / 80.0 - 1.0) * std::exp(-(L / 20.0) * (L / 20.0)));
  return std::max(v, 0.0);
}

CodeValue deflection_span_ratio() { return {600.0, "EN 1990 A2.4.4.2.3(2)", false}; }

const std::vector<ComfortLevel>& comfort_levels() {
  static const std::vector<ComfortLevel> levels = {{"very good", 1.0}, {"good", 1.3}, {"acceptable", 2.0}};
  return levels;
}

CodeValue twist_limit_mm_per_3m(double line_speed_kmh) {
  const double limit = line_speed_kmh <= 120.0 ? 4.5 : line_speed_kmh <= 200.0 ? 3.0 : 1.5;
  return {limit, "EN 1990 A2.4.4.2.2", false};
}

CodeValue unloading_ratio_limit() { return {0.6, "common practice (EN 14363 quasi-static)", false}; }

}  // namespace railvsi
