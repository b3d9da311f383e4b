#include "compliance/stored_checks.hpp"

#include <algorithm>

#include <fmt/format.h>

#include "compliance/check_limits.hpp"
#include "compliance/code_values.hpp"

namespace railvsi {
namespace {

using nlohmann::json;

bool ballasted(const json& checks) {
  return checks.value("track_type", std::string("ballasted")) != "direct_fastening";
}

void deck_acceleration_limit(const json& checks, CheckResult& c) {
  const CodeValue code =
      ballasted(checks) ? deck_acceleration_limit_ballasted_mps2() : deck_acceleration_limit_direct_fastening_mps2();
  c.clause = code.clause;
  c.limit = *check_limit(checks, c.quantity);
  if (checks.contains("deck_acceleration_limit_mps2")) {
    c.limit_verified = c.limit == code.value && code.verified;
    c.note = c.limit == code.value ? "" : "Limit given in the study's checks.";
  } else {
    c.limit_verified = code.verified;
    c.note = std::string(ballasted(checks) ? "Ballasted track" : "Direct fastening") +
             " limit (checks.track_type); frequencies up to the cut-off above.";
  }
}

void given_limit(const json& checks, CheckResult& c) {
  c.clause = "limit given in the study's checks";
  c.limit = *check_limit(checks, c.quantity);
  c.limit_verified = true;
}

void unloading_limit(const json& checks, CheckResult& c) {
  const CodeValue code = unloading_ratio_limit();
  c.limit = *check_limit(checks, c.quantity);
  c.clause = checks.contains("max_unloading_ratio") ? "limit given in the study's checks" : code.clause;
  c.limit_verified = checks.contains("max_unloading_ratio");
  c.note = "1 means the wheel lost contact.";
}

void comfort_limit(const json& checks, CheckResult& c) {
  c.clause = kComfortClause;
  c.limit = *check_limit(checks, c.quantity);
  c.limit_verified = kComfortVerified;
  c.note = checks.contains("carbody_acceleration_limit_mps2")
               ? "Limit given in the study's checks."
               : "Required level: " + checks.value("comfort_level", std::string("very good")) +
                     " (checks.comfort_level).";
}

void comfort_level_reached(const json&, CheckResult& c) {
  if (!c.governing || !c.governing->value) return;
  std::string achieved = "below acceptable";
  for (const ComfortLevel& l : comfort_levels())
    if (*c.governing->value <= l.b_v_mps2) {
      achieved = l.name;
      break;
    }
  c.note += " Level reached by the governing case: " + achieved + ".";
}

void nothing_after(const json&, CheckResult&) {}

const std::vector<StoredCheckRule> kRules = {
    {"deck_acceleration", "Peak deck acceleration (filtered)", "deck_acceleration_mps2", "m/s2", false,
     [](const json&, bool) { return true; }, deck_acceleration_limit, nothing_after},
    {"deck_displacement", "Peak deck displacement", "deck_displacement_m", "m", false,
     [](const json& checks, bool) { return checks.contains("deck_displacement_limit_m"); }, given_limit,
     nothing_after},
    {"wheel_unloading", "Wheel unloading dQ/Q", "unloading_ratio", "", true,
     [](const json& checks, bool any) { return any || checks.contains("max_unloading_ratio"); }, unloading_limit,
     nothing_after},
    {"passenger_comfort", "Passenger comfort: car-body acceleration", "carbody_acceleration_mps2", "m/s2", true,
     [](const json& checks, bool any) { return any || checks.contains("carbody_acceleration_limit_mps2"); },
     comfort_limit, comfort_level_reached},
};

std::optional<double> value_of(const std::map<std::string, std::optional<double>>& m, const std::string& quantity) {
  const auto it = m.find(quantity);
  return it == m.end() ? std::nullopt : it->second;
}

}  // namespace

const std::vector<StoredCheckRule>& stored_check_rules() { return kRules; }

std::vector<CheckResult> evaluate_stored_checks(const json& checks, const std::vector<StoredCase>& cases) {
  const auto axle_force_cases = static_cast<std::size_t>(
      std::count_if(cases.begin(), cases.end(), [](const StoredCase& c) { return c.axle_forces; }));
  std::vector<CheckResult> out;
  for (const StoredCheckRule& rule : kRules) {
    const bool any_value = std::any_of(cases.begin(), cases.end(), [&](const StoredCase& c) {
      return value_of(c.values, rule.quantity).has_value();
    });
    if (!rule.applies(checks, any_value)) continue;
    CheckResult check;
    check.id = rule.id;
    check.title = rule.title;
    check.quantity = rule.quantity;
    check.unit = rule.unit;
    rule.limit(checks, check);
    std::vector<CheckCase> checked;
    for (const StoredCase& c : cases) {
      if (rule.vehicles && c.axle_forces) continue;
      CheckCase k = c.at;
      k.value = value_of(c.values, rule.quantity);
      k.error_estimate = value_of(c.error_estimates, rule.quantity);
      checked.push_back(std::move(k));
    }
    CheckResult result = evaluate_upper_limit(std::move(check), checked);
    // Wheels and car bodies concern trains of vehicles: the cases of a
    // train given as axle forces are left out rather than counted missing.
    if (rule.vehicles && axle_force_cases > 0) {
      if (checked.empty()) {
        result.verdict = Verdict::kNotEvaluated;
        result.note += " Not evaluated: every train of the study is given as axle forces (a load model has no wheels "
                       "or car bodies).";
      } else {
        result.note += fmt::format(" The {} cases of trains given as axle forces (load models: no wheels or car "
                                   "bodies) are not part of this check.",
                                   axle_force_cases);
      }
    }
    rule.after(checks, result);
    out.push_back(std::move(result));
  }
  return out;
}

}  // namespace railvsi
