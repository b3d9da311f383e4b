#pragma once
// The speeds of a study: a list, or {"from", "to", "step"} with both ends;
// and the range EN 1991-2 6.4.6.2 asks for, built from the line speed.
#include <cstddef>
#include <optional>
#include <vector>

#include <nlohmann/json.hpp>

namespace railvsi::scheduler {

// Speeds in km/h, rounded to 1e-9 km/h so that 100 + 3 * 0.1 is 100.3 and
// the job ids do not depend on floating-point accumulation. InputError at
// /speeds_kmh/... for an empty range or more than max_count speeds.
std::vector<double> expand_speeds(const nlohmann::json& speeds_kmh, std::size_t max_count);

// The resonance speeds v_i = f0 D / i (i = 1..4) in km/h of a train whose
// loads repeat every D m (HSLM-A coach length, HSLM-B spacing), within
// [min_kmh, max_kmh], highest first; empty when D or f0 is not positive.
std::vector<double> resonance_speeds_kmh(double f0_hz, double spacing_m, double min_kmh, double max_kmh);

// EN 1991-2 6.4.6.2: speeds from a start speed (40 m/s = 144 km/h) up to the
// maximum design speed 1.2 x the maximum line speed, in steps, with smaller
// steps near the resonance speeds.
struct LineSpeedRange {
  double line_speed_kmh = 0.0;
  double min_kmh = 144.0;
  double step_kmh = 10.0;
  double max_kmh() const { return rounded_speed_kmh(1.2 * line_speed_kmh); }
  static double rounded_speed_kmh(double speed_kmh);
};

// The study's "line_speed_kmh" (with "speed_min_kmh", "speed_step_kmh"), or
// nullopt when it has none. InputError at its JSON path when the start is
// above the maximum design speed.
std::optional<LineSpeedRange> line_speed_range(const nlohmann::json& study);

// The speeds of the range for one train on one structure: min, min + step,
// ... and the maximum design speed; then, for each resonance speed v_r in the
// range, v_r (1 + k zeta / 2) for k = -4..4 (inside the range): 9 speeds
// spanning twice the half-power band v_r (1 +- zeta) of a resonance with
// damping ratio zeta, so that a sample lies within zeta/4 of the peak
// frequency (at least 97 % of a single-mode peak: 1/sqrt(1 + 1/16)).
// Sorted, without repeats. zeta <= 0 (unknown) counts as 0.005.
std::vector<double> line_speed_speeds(const LineSpeedRange& range, double f0_hz, double spacing_m,
                                      double damping_ratio, std::size_t max_count);

}  // namespace railvsi::scheduler
