#pragma once
// The speeds of a study: a list, or {"from", "to", "step"} with both ends.
#include <cstddef>
#include <vector>

#include <nlohmann/json.hpp>

namespace railvsi::scheduler {

// Speeds in km/h, rounded to 1e-9 km/h so that 100 + 3 * 0.1 is 100.3 and
// the job ids do not depend on floating-point accumulation. InputError at
// /speeds_kmh/... for an empty range or more than max_count speeds.
std::vector<double> expand_speeds(const nlohmann::json& speeds_kmh, std::size_t max_count);

}  // namespace railvsi::scheduler
