#include "compliance/check_limits.hpp"

#include <string>

#include "compliance/code_values.hpp"

namespace railvsi {

std::optional<double> check_limit(const nlohmann::json& checks, std::string_view quantity) {
  const auto given = [&](const char* key) -> std::optional<double> {
    if (checks.contains(key)) return checks.at(key).get<double>();
    return std::nullopt;
  };
  if (quantity == "deck_acceleration_mps2") {
    const bool ballasted = checks.value("track_type", std::string("ballasted")) != "direct_fastening";
    return given("deck_acceleration_limit_mps2")
        .value_or(ballasted ? deck_acceleration_limit_ballasted_mps2().value
                            : deck_acceleration_limit_direct_fastening_mps2().value);
  }
  if (quantity == "deck_displacement_m") return given("deck_displacement_limit_m");
  if (quantity == "unloading_ratio") return given("max_unloading_ratio").value_or(unloading_ratio_limit().value);
  if (quantity == "carbody_acceleration_mps2") {
    if (const auto limit = given("carbody_acceleration_limit_mps2")) return limit;
    const std::string level = checks.value("comfort_level", std::string("very good"));
    double limit = comfort_levels().front().b_v_mps2;
    for (const ComfortLevel& l : comfort_levels())
      if (level == l.name) limit = l.b_v_mps2;
    return limit;
  }
  return std::nullopt;
}

}  // namespace railvsi
