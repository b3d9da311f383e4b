#include "study/speed_list.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "core/input_error.hpp"

namespace railvsi::scheduler {
namespace {

double rounded(double speed_kmh) { return std::round(speed_kmh * 1e9) / 1e9; }

}  // namespace

std::vector<double> expand_speeds(const nlohmann::json& speeds_kmh, std::size_t max_count) {
  std::vector<double> speeds;
  if (speeds_kmh.is_array()) {
    for (const auto& v : speeds_kmh) speeds.push_back(rounded(v.get<double>()));
    return speeds;
  }
  const double from = speeds_kmh.at("from").get<double>(), to = speeds_kmh.at("to").get<double>(),
               step = speeds_kmh.at("step").get<double>();
  if (to < from) throw InputError("/speeds_kmh/to", fmt::format("must be >= from ({})", from));
  // Both ends included; the tolerance keeps 'to' when (to - from)/step is a
  // whole number spoilt by round-off. A 'to' off the step's grid is added
  // after the last step below it: the top of a range is usually the maximum
  // design speed, the one speed a study must not drop.
  const double intervals = std::floor((to - from) / step + 1e-9);
  // A 'to' within a millionth of a step of the grid is on it (350.0000005
  // with steps of 50 is 350, not a second job beside it).
  const bool to_off_grid = to - rounded(from + intervals * step) > 1e-6 * step;
  const double count = intervals + 1.0 + (to_off_grid ? 1.0 : 0.0);
  if (count > static_cast<double>(max_count))
    throw InputError("/speeds_kmh/step",
                     fmt::format("gives {:.0f} speeds, more than the {} jobs a study may have", count, max_count));
  for (long k = 0; k <= static_cast<long>(intervals); ++k) speeds.push_back(rounded(from + static_cast<double>(k) * step));
  if (to_off_grid) speeds.push_back(rounded(to));
  return speeds;
}

double LineSpeedRange::rounded_speed_kmh(double speed_kmh) { return rounded(speed_kmh); }

std::vector<double> resonance_speeds_kmh(double f0_hz, double spacing_m, double min_kmh, double max_kmh) {
  std::vector<double> speeds;
  if (!(f0_hz > 0.0) || !(spacing_m > 0.0)) return speeds;
  for (int i = 1; i <= 4; ++i) {
    const double v_kmh = f0_hz * spacing_m / i * 3.6;
    if (v_kmh >= min_kmh && v_kmh <= max_kmh) speeds.push_back(v_kmh);
  }
  return speeds;
}

std::optional<LineSpeedRange> line_speed_range(const nlohmann::json& study) {
  if (!study.contains("line_speed_kmh")) return std::nullopt;
  LineSpeedRange r;
  r.line_speed_kmh = study.at("line_speed_kmh").get<double>();
  r.min_kmh = study.value("speed_min_kmh", r.min_kmh);
  r.step_kmh = study.value("speed_step_kmh", r.step_kmh);
  if (r.min_kmh > r.max_kmh())
    throw InputError(study.contains("speed_min_kmh") ? "/speed_min_kmh" : "/line_speed_kmh",
                     fmt::format("the speeds start at {} km/h, above the maximum design speed 1.2 x {} = {} km/h "
                                 "(EN 1991-2 6.4.6.2); give a lower speed_min_kmh",
                                 r.min_kmh, r.line_speed_kmh, r.max_kmh()));
  return r;
}

std::vector<double> line_speed_speeds(const LineSpeedRange& range, double f0_hz, double spacing_m,
                                      double damping_ratio, std::size_t max_count) {
  const double max_kmh = range.max_kmh();
  std::vector<double> speeds;
  try {
    speeds = expand_speeds({{"from", range.min_kmh}, {"to", max_kmh}, {"step", range.step_kmh}}, max_count);
  } catch (const InputError& e) {
    throw InputError("/speed_step_kmh", e.what());
  }
  const double zeta = damping_ratio > 0.0 ? damping_ratio : 0.005;
  for (double v_r : resonance_speeds_kmh(f0_hz, spacing_m, range.min_kmh, max_kmh))
    for (int k = -4; k <= 4; ++k) {
      const double v = rounded(v_r * (1.0 + 0.5 * k * zeta));
      if (v >= range.min_kmh && v <= max_kmh) speeds.push_back(v);
    }
  std::sort(speeds.begin(), speeds.end());
  speeds.erase(std::unique(speeds.begin(), speeds.end()), speeds.end());
  return speeds;
}

}  // namespace railvsi::scheduler
