#pragma once
// --fail-on-exceeded: one rule for vsi query, vsi run and vsi report
// (README "Exit codes").
#include <string>

#include "compliance/check_verdict.hpp"
#include "query/study_results.hpp"
#include "report/compliance_report.hpp"
#include "store/sqlite.hpp"

namespace railvsi::cli {

inline constexpr const char* kFailOnExceededHelp =
    "Exit 4 when a check fails, 5 when a check is incomplete (a case without a value) and none fails";

// 4 when the overall verdict is FAIL (a missing case cannot undo an
// exceedance, so FAIL wins), 5 when it is INCOMPLETE or NOT EVALUATED
// (nothing judged is never a pass), 0 when every check passes.
int verdict_exit_code(Verdict overall);

// The checks of vsi report over `jobs` (the study's jobs as read by the
// caller), without re-simulating the governing cases.
ComplianceReport judge_jobs(scheduler::Database& db, const std::string& study_id,
                            const std::vector<scheduler::JobResult>& jobs);

// The exit codes for a command's --help; with_failed_jobs: vsi run's 3.
std::string verdict_exit_footer(bool with_failed_jobs);

}  // namespace railvsi::cli
