#pragma once
// The EN checks on stored envelope quantities as one table of rules: each
// rule names its quantity, where its limit comes from and whether it
// concerns wheels and car bodies; evaluate_stored_checks applies the table
// to the cases of a study's jobs. Plain data in, verdicts out: testable
// without a store.
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "compliance/check_verdict.hpp"

namespace railvsi {

// One job's values for the stored checks.
struct StoredCase {
  CheckCase at;  // train, speed, profile, job id and bound (value and estimate are set per check)
  // Its train is axle forces (a load model): it has no wheel or car body.
  bool axle_forces = false;
  std::map<std::string, std::optional<double>> values;           // quantity -> overall value
  std::map<std::string, std::optional<double>> error_estimates;  // quantity -> estimate of accuracy.verify
};

struct StoredCheckRule {
  const char* id;
  const char* title;
  const char* quantity;
  const char* unit;
  // Wheels and car bodies: a train of axle forces is left out of the check.
  bool vehicles;
  // Whether the study checks it: from its "checks" and whether any case has
  // a value of the quantity.
  bool (*applies)(const nlohmann::json& checks, bool any_value);
  // Sets limit, clause, limit_verified and note from the study's checks
  // (a limit it gives, else the code's).
  void (*limit)(const nlohmann::json& checks, CheckResult& check);
  // After the verdict, e.g. the comfort level the governing case reaches.
  void (*after)(const nlohmann::json& checks, CheckResult& check);
};

// deck acceleration (EN 1990 A2.4.4.2.1(4)P), deck displacement (a limit the
// study gives), wheel unloading, passenger comfort (EN 1990 A2.4.4.3.2), in
// the report's order.
const std::vector<StoredCheckRule>& stored_check_rules();

// Every rule of the table that applies, evaluated over the cases (the
// verdict rules of check_verdict.hpp).
std::vector<CheckResult> evaluate_stored_checks(const nlohmann::json& checks, const std::vector<StoredCase>& cases);

}  // namespace railvsi
