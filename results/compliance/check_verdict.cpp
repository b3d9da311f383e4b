#include "compliance/check_verdict.hpp"

#include <cmath>
#include <map>
#include <tuple>

namespace railvsi {

const char* verdict_name(Verdict v) {
  switch (v) {
    case Verdict::kPass: return "PASS";
    case Verdict::kFail: return "FAIL";
    case Verdict::kIncomplete: return "INCOMPLETE";
    case Verdict::kNotEvaluated: return "NOT EVALUATED";
  }
  return "NOT EVALUATED";
}

CheckResult evaluate_upper_limit(CheckResult check, const std::vector<CheckCase>& cases) {
  check.cases = static_cast<int>(cases.size());
  check.missing = 0;
  check.governing.reset();
  check.all_cases = cases;
  bool exceeded = false;
  for (const CheckCase& c : cases) {
    if (!c.value || !std::isfinite(*c.value)) {
      ++check.missing;
      continue;
    }
    if (*c.value > check.limit) exceeded = true;
    // Equal values (a moving-force job is the same with or without a
    // profile): the lowest speed, then profile label, governs, as in the
    // envelope over speeds (envelopes/speed_envelope.cpp), so both name one case.
    const auto governs = [&c](const CheckCase& g) {
      if (*c.value != *g.value) return *c.value > *g.value;
      return std::tie(c.speed_kmh, c.irregularity, c.variant, c.location) <
             std::tie(g.speed_kmh, g.irregularity, g.variant, g.location);
    };
    if (!check.governing || governs(*check.governing)) check.governing = c;
  }
  if (cases.empty())
    check.verdict = Verdict::kIncomplete;
  else
    check.verdict = exceeded ? Verdict::kFail : check.missing > 0 ? Verdict::kIncomplete : Verdict::kPass;
  return check;
}

std::vector<CheckResult> per_train(const CheckResult& check) {
  std::vector<std::string> order;
  std::map<std::string, std::vector<CheckCase>> by_train;
  for (const CheckCase& c : check.all_cases) {
    auto [it, fresh] = by_train.try_emplace(c.train);
    if (fresh) order.push_back(c.train);
    it->second.push_back(c);
  }
  std::vector<CheckResult> out;
  for (const std::string& t : order) {
    CheckResult one = evaluate_upper_limit(check, by_train.at(t));
    one.note.clear();  // the check's note speaks of its overall governing case
    out.push_back(std::move(one));
  }
  return out;
}

Verdict overall_verdict(const std::vector<CheckResult>& checks) {
  bool any = false, incomplete = false;
  for (const CheckResult& c : checks) {
    if (c.verdict == Verdict::kNotEvaluated) continue;
    any = true;
    if (c.verdict == Verdict::kFail) return Verdict::kFail;
    if (c.verdict == Verdict::kIncomplete) incomplete = true;
  }
  if (!any) return Verdict::kNotEvaluated;
  return incomplete ? Verdict::kIncomplete : Verdict::kPass;
}

}  // namespace railvsi
