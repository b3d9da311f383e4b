#include "cli/verdict_exit.hpp"

#include "cli/commands.hpp"
#include "query/compliance_data.hpp"

namespace railvsi::cli {

int verdict_exit_code(Verdict overall) {
  switch (overall) {
    case Verdict::kPass: return kExitOk;
    case Verdict::kFail: return kExitCheckFailed;
    case Verdict::kIncomplete:
    case Verdict::kNotEvaluated: return kExitCheckIncomplete;
  }
  return kExitCheckIncomplete;
}

ComplianceReport judge_jobs(scheduler::Database& db, const std::string& study_id,
                            const std::vector<scheduler::JobResult>& jobs) {
  scheduler::ComplianceOptions options;
  options.histories = false;
  options.jobs = &jobs;
  return scheduler::build_compliance_report(db, study_id, options);
}

std::string verdict_exit_footer(bool with_failed_jobs) {
  std::string text = "Exit codes: 0 success; 1 runtime failure; 2 invalid input or usage";
  if (with_failed_jobs) text += "; 3 the study finished with failed jobs";
  text += ". With --fail-on-exceeded: 4 a check fails (this wins";
  text += with_failed_jobs ? " over 3 and 5); 5 a check is incomplete and no job failed" : " over 5); 5 a check is incomplete";
  return text + " (a case without a value: cancelled, failed, not run), or no check could be evaluated.";
}

}  // namespace railvsi::cli
