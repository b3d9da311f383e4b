#include "cli/line_study_output.hpp"

#include <utility>
#include <vector>

#include <fmt/format.h>

#include "core/terminal_text.hpp"
#include "query/bridge_results.hpp"
#include "query/compliance_data.hpp"
#include "query/line_table.hpp"
#include "query/study_report.hpp"

namespace railvsi::cli {
namespace {

scheduler::ComplianceOptions verdicts_only() {
  scheduler::ComplianceOptions o;
  o.histories = false;
  o.checks_only = true;
  return o;
}

}  // namespace

std::optional<Verdict> write_line_study_by_bridge(scheduler::Database& db, const scheduler::StudyInfo& info,
                                                  const LineStudyOutputOptions& options, std::ostream& out) {
  const bool table = options.format != "csv";
  if (table)
    out << fmt::format("study {} ({}): {} jobs in {} bridges, a table per bridge (vsi query --line: a row per "
                       "bridge)\n",
                       info.id.substr(0, 12), scheduler::terminal_safe(info.name), info.job_count,
                       scheduler::study_structure_names(db, info.id).size());
  std::vector<CheckResult> all_checks;
  scheduler::BridgeReader reader(db, info.id, scheduler::BridgeFields::kAll);
  std::string name;
  std::vector<scheduler::JobResult> jobs;
  bool first = true;
  while (reader.next(name, jobs)) {
    if (table) {
      out << "\nbridge " << scheduler::terminal_safe(name) << '\n' << scheduler::format_table(info, jobs);
    } else {
      // Every bridge of a line has the same columns (the variants are the
      // study's): the header once.
      const std::string csv = scheduler::format_csv(jobs);
      out << (first ? std::string_view(csv) : std::string_view(csv).substr(csv.find('\n') + 1));
    }
    if (options.judge) {
      scheduler::ComplianceOptions o = verdicts_only();
      o.jobs = &jobs;
      const ComplianceReport report = scheduler::build_compliance_report(db, info.id, o);
      if (table) out << scheduler::format_verdict_lines(report.checks, report.overall);
      all_checks.insert(all_checks.end(), report.checks.begin(), report.checks.end());
    }
    first = false;
  }
  if (!options.judge) return std::nullopt;
  return overall_verdict(all_checks);
}

Verdict write_line_table(scheduler::Database& db, const std::string& study_id, std::ostream& out) {
  const std::vector<LineBridge> bridges = scheduler::line_bridges(db, study_id, verdicts_only());
  out << scheduler::format_line_table(bridges);
  out << fmt::format("a bridge's jobs: vsi query --study {} --structure NAME; every job: without --structure\n",
                     study_id.substr(0, 12));
  std::vector<CheckResult> all;
  for (const LineBridge& b : bridges) all.insert(all.end(), b.report.checks.begin(), b.report.checks.end());
  return overall_verdict(all);
}

}  // namespace railvsi::cli
