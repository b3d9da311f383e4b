#pragma once
// The verdict of one compliance check over the cases of a study. A check
// is FAIL as soon as one case exceeds its limit (a missing case cannot
// undo an exceedance), INCOMPLETE when no case exceeds but some case has no
// value (cancelled, failed or not yet run: never "ok" on missing data), and
// PASS only when every case has a value within the limit.
#include <optional>
#include <string>
#include <vector>

namespace railvsi {

enum class Verdict { kPass, kFail, kIncomplete, kNotEvaluated };
const char* verdict_name(Verdict v);  // "PASS", "FAIL", "INCOMPLETE", "NOT EVALUATED"

// One case of a check: a job's value of the checked quantity.
struct CheckCase {
  std::string train;
  double speed_kmh = 0.0;
  std::string irregularity;
  std::optional<double> value;  // nullopt: no value (the job did not produce one)
  std::string job_id{};    // the job that gives the value; empty when the case is not one job
  std::string location{};  // output point of the value, when the check names one
  std::string variant{};   // bound of the structure (EN 1991-2 6.4.6.3); empty when the study has none
  // (value - verified) / verified from the study's accuracy.verify; absent when not verified.
  std::optional<double> error_estimate{};
};

struct CheckResult {
  std::string id;        // machine name, e.g. "deck_acceleration"
  std::string title;     // for people
  std::string clause;    // where the limit comes from
  std::string quantity;  // envelope quantity checked
  std::string unit;
  double limit = 0.0;
  bool limit_verified = false;  // false: printed "unverified"
  Verdict verdict = Verdict::kNotEvaluated;
  // The governing case (largest value); absent when no case has a value.
  std::optional<CheckCase> governing;
  int cases = 0;
  int missing = 0;
  std::string note;  // e.g. how the limit was derived, or why not evaluated
  std::vector<CheckCase> all_cases;  // what the verdict was made of (set by evaluate_upper_limit)
};

// Verdict and governing case of `cases` against an upper limit.
CheckResult evaluate_upper_limit(CheckResult check, const std::vector<CheckCase>& cases);

// The check over the cases of each train separately (trains in the order
// of their first case), by the same rules; empty when it has no cases.
std::vector<CheckResult> per_train(const CheckResult& check);

// The overall verdict of several checks: FAIL if any fails, else
// INCOMPLETE if any is incomplete, else PASS (checks not evaluated do not
// count; none evaluated is NOT EVALUATED).
Verdict overall_verdict(const std::vector<CheckResult>& checks);

}  // namespace railvsi
