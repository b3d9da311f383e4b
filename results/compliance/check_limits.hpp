#pragma once
// The limit each stored quantity is checked against, as the compliance
// report applies it: the value given in the study's checks, else the code's
// (deck acceleration by checks.track_type, EN 1990 A2.4.4.2.1; car-body
// acceleration by checks.comfort_level, A2.4.4.3.1; wheel unloading). The
// report, the verdict lines and the envelope table all read it here.
#include <optional>
#include <string_view>

#include <nlohmann/json.hpp>

namespace railvsi {

// nullopt: the quantity has no limit in these checks (deck displacement
// without deck_displacement_limit_m, or a quantity no check reads).
std::optional<double> check_limit(const nlohmann::json& checks, std::string_view quantity);

}  // namespace railvsi
