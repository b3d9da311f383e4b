#include <iostream>
#include <optional>
#include <utility>

#include "cli/commands.hpp"
#include "cli/line_study_output.hpp"
#include "cli/service_commands.hpp"
#include "cli/service_store.hpp"
#include "cli/verdict_exit.hpp"
#include "core/terminal_text.hpp"
#include "query/line_table.hpp"
#include "query/static_effects.hpp"
#include "query/study_report.hpp"
#include "queue/job_queue.hpp"
#include "store/store_check.hpp"

namespace railvsi::cli {

int query_command(const ServiceArgs& args) { return write_query(args, std::cout, std::cerr); }

int write_query(const ServiceArgs& args, std::ostream& out_text, std::ostream& err) {
  const auto db = open_store(args.db, scheduler::OpenMode::kReadOnly);
  const auto id = find_study(*db, args.study_id);
  if (!id) return kExitInvalidInput;
  const scheduler::QueryFilter filter{*id,          args.train,        args.speed_min_kmh,
                                      args.speed_max_kmh, args.irregularity, args.structure};
  // Without filters the line table reads the study bridge by bridge, every
  // job with its envelope values, and refuses a done job without any itself.
  const bool whole = !filter.train && !filter.speed_min_kmh && !filter.speed_max_kmh && !filter.irregularity &&
                     !filter.structure;
  scheduler::require_consistent_study(*db, *id,
                                      args.line && whole ? scheduler::StudyCheck::kLinks : scheduler::StudyCheck::kAll);
  if (const auto why = scheduler::filter_error(*db, filter)) {
    err << "error: " << scheduler::terminal_safe(*why) << '\n';  // it lists the study's names
    return kExitInvalidInput;
  }
  if (args.wide && args.format != "csv") {
    err << "error: --wide applies to --format csv\n";
    return kExitInvalidInput;
  }
  const scheduler::StudyInfo info = scheduler::study_info(*db, *id);
  if (args.line) {
    if (scheduler::study_structure_names(*db, *id).empty()) {
      std::cerr << "error: --line: the study " << id->substr(0, 12) << " has one structure (no \"structures\")\n";
      return kExitInvalidInput;
    }
    scheduler::ComplianceOptions options;
    options.histories = false;
    options.checks_only = true;
    // Without filters the study is read bridge by bridge; a filter judges the jobs it keeps.
    const auto bridges = whole ? scheduler::line_bridges(*db, *id, options)
                               : scheduler::line_bridges(*db, *id, scheduler::study_results(*db, filter), options);
    if (args.format == "csv") std::cout << scheduler::format_line_csv(bridges);
    else if (args.format == "json") std::cout << scheduler::format_line_json(bridges).dump(2) << '\n';
    else std::cout << scheduler::format_line_table(bridges);
    if (!args.fail_on_exceeded) return kExitOk;
    std::vector<CheckResult> all;
    for (const LineBridge& b : bridges) all.insert(all.end(), b.report.checks.begin(), b.report.checks.end());
    return verdict_exit_code(overall_verdict(all));
  }
  // A whole line study's table or CSV is written bridge by bridge, one
  // bridge's jobs in memory at a time (900,000 jobs read at once took 5.2 GB).
  // JSON and the wide CSV (its columns are every bridge's points) read all.
  if (whole && args.format != "json" && !args.wide && !scheduler::study_structure_names(*db, *id).empty()) {
    const auto verdict = write_line_study_by_bridge(*db, info, {args.format, args.fail_on_exceeded}, out_text);
    return verdict ? verdict_exit_code(*verdict) : kExitOk;
  }
  const auto jobs = scheduler::study_results(*db, filter);
  // The verdicts of vsi report's checks, over the jobs shown.
  std::optional<ComplianceReport> judged;
  std::string not_judged;
  if (args.format == "json" || args.fail_on_exceeded) {
    try {
      judged = judge_jobs(*db, *id, jobs);
    } catch (const InputError& e) {  // a stored scene that no longer loads (e.g. its train file removed)
      not_judged = e.describe();
      err << "warning: the checks cannot be evaluated: " << scheduler::terminal_safe(not_judged) << '\n';
    }
  }
  if (args.format == "csv") {
    out_text << (args.wide ? scheduler::format_wide_csv(jobs) : scheduler::format_csv(jobs));
  } else if (args.format == "json") {
    nlohmann::ordered_json out = scheduler::format_json(info, jobs);
    out["verdict"] = verdict_name(judged ? judged->overall : Verdict::kNotEvaluated);
    out["checks"] = judged ? scheduler::format_checks_json(judged->checks, jobs) : nlohmann::ordered_json::array();
    if (!judged) out["checks_error"] = not_judged;
    std::vector<std::string> notes;
    try {
      const auto increments = scheduler::dynamic_increments(*db, jobs, notes);
      out["dynamic_increment"] = scheduler::dynamic_increments_json(increments, notes);
    } catch (const std::exception& e) {
      out["dynamic_increment"] = {{"error", std::string("static response not computed: ") + e.what()}};
    }
    out_text << out.dump(2) << '\n';
  } else {
    out_text << scheduler::format_table(info, jobs);
    if (judged) out_text << scheduler::format_verdict_lines(judged->checks, judged->overall);
  }
  if (!args.fail_on_exceeded) return kExitOk;
  return verdict_exit_code(judged ? judged->overall : Verdict::kNotEvaluated);
}

namespace {

// A change to the jobs of --study: prints "study <id>: <n> <what>".
int change_study(const ServiceArgs& args, std::int64_t (*change)(scheduler::Database&, const std::string&),
                 const char* what) {
  const auto db = open_store(args.db, scheduler::OpenMode::kExisting);
  const auto id = find_study(*db, args.study_id);
  if (!id) return kExitInvalidInput;
  std::cout << "study " << *id << ": " << change(*db, *id) << " " << what << "\n";
  return kExitOk;
}

}  // namespace

int cancel_command(const ServiceArgs& args) {
  const auto db = open_store(args.db, scheduler::OpenMode::kExisting);
  const auto id = find_study(*db, args.study_id);
  if (!id) return kExitInvalidInput;
  const scheduler::CancelResult r = scheduler::cancel_study(*db, *id);
  std::cout << "study " << *id << ": " << r.cancelled << " jobs cancelled";
  if (r.left_for_other_studies > 0)
    std::cout << ", " << r.left_for_other_studies << " left queued for other unfinished studies that share them";
  std::cout << "\n";
  return kExitOk;
}

int retry_command(const ServiceArgs& args) { return change_study(args, scheduler::retry_study, "jobs queued again"); }

}  // namespace railvsi::cli
