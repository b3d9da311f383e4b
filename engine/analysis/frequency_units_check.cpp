#include "analysis/frequency_units_check.hpp"

#include <cmath>

#include <fmt/format.h>

namespace railvsi {

std::optional<std::string> frequency_units_warning(double f1_hz) {
  const double factor = std::sqrt(1000.0);
  if (f1_hz > kPlausibleFirstFrequencyMaxHz)
    return fmt::format("first natural frequency {:.4g} Hz is above {} Hz: is M in t (tonnes) instead of kg, or K in "
                       "N/mm with M in kg? With M in kg it would be {:.4g} Hz. railvsi reads K in N/m, M in kg",
                       f1_hz, kPlausibleFirstFrequencyMaxHz, f1_hz / factor);
  if (f1_hz < kPlausibleFirstFrequencyMinHz)
    return fmt::format("first natural frequency {:.4g} Hz is below {} Hz: is K in kN/m instead of N/m, or M in g? "
                       "With K in N/m it would be {:.4g} Hz. railvsi reads K in N/m, M in kg (a mechanism gives a "
                       "frequency near 0 too)",
                       f1_hz, kPlausibleFirstFrequencyMinHz, f1_hz * factor);
  return std::nullopt;
}

}  // namespace railvsi
