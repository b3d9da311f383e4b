#pragma once
// A plausibility check of an imported model's units: railway bridges have
// their first natural frequency between about 0.5 and 100 Hz (EN 1991-2
// Figure 6.10 draws its limits for spans of 4-100 m between 1.5 and about
// 40 Hz). A first frequency far outside that band usually means a unit
// mistake in K or M; since f = sqrt(k/m)/(2 pi), a factor of 1000 in either
// moves it by sqrt(1000) = 31.6.
#include <optional>
#include <string>

namespace railvsi {

constexpr double kPlausibleFirstFrequencyMinHz = 0.5;
constexpr double kPlausibleFirstFrequencyMaxHz = 100.0;

// The warning for a first frequency outside [0.5, 100] Hz, naming the likely
// unit mistake and the frequency it would give corrected; nullopt inside.
std::optional<std::string> frequency_units_warning(double first_frequency_hz);

}  // namespace railvsi
