#include "study/speed_list.hpp"

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
  // whole number spoilt by round-off.
  const double intervals = std::floor((to - from) / step + 1e-9);
  if (intervals + 1.0 > static_cast<double>(max_count))
    throw InputError("/speeds_kmh/step",
                     fmt::format("gives {:.0f} speeds, more than the {} jobs a study may have", intervals + 1.0, max_count));
  for (long k = 0; k <= static_cast<long>(intervals); ++k) speeds.push_back(rounded(from + static_cast<double>(k) * step));
  return speeds;
}

}  // namespace railvsi::scheduler
