#include "cli/report_command.hpp"

#include <chrono>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <iostream>

#include <fmt/format.h>

#include "cli/commands.hpp"
#include "cli/service_store.hpp"
#include "cli/verdict_exit.hpp"
#include "query/compliance_data.hpp"
#include "report/compliance_report.hpp"
#include "store/store_check.hpp"

namespace railvsi::cli {
namespace {

// The date line: now, or SOURCE_DATE_EPOCH when set (the reproducible-builds
// convention), so that a report can be made byte for byte again.
std::string report_date() {
  std::time_t t = std::time(nullptr);
  if (const char* epoch = std::getenv("SOURCE_DATE_EPOCH")) {
    char* end = nullptr;
    const long long v = std::strtoll(epoch, &end, 10);
    if (end != epoch && *end == '\0' && v >= 0) t = static_cast<std::time_t>(v);
  }
  std::tm tm{};
  gmtime_r(&t, &tm);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%d %H:%M UTC", &tm);
  return buf;
}

}  // namespace

ReportCommand::ReportCommand(CLI::App& app) {
  report_ = app.add_subcommand(
      "report", "Write the compliance report of a study (one self-contained HTML file: verdicts, plots, governing "
                "cases, model, inputs)");
  report_->add_option("--db", args_.db, "Study database (SQLite file)")->capture_default_str();
  report_->add_option("--study", args_.study_id, "Study id (a unique prefix of at least 6 digits)")->required();
  report_->add_option("--out", args_.out, "Report file (default: report-<study id>.html)");
  report_->add_flag("!--no-histories", args_.histories, "Do not re-simulate the governing cases");
  report_->add_flag("--fail-on-exceeded", args_.fail_on_exceeded, kFailOnExceededHelp);
  report_->footer(verdict_exit_footer(false));
}

std::optional<int> ReportCommand::run_parsed() const {
  if (!report_->parsed()) return std::nullopt;
  return report_command(args_);
}

int report_command(const ReportArgs& args) {
  auto opened = open_study(args.db, args.study_id);
  if (!opened) return kExitInvalidInput;
  const auto& db = opened->db;
  const std::optional<std::string> id = opened->id;
  // A damaged file is reported, never turned into a partial report.
  scheduler::require_consistent_study(*db, *id);
  scheduler::ComplianceOptions options;
  options.version = RAILVSI_VERSION_STRING;
  options.date = report_date();
  options.histories = args.histories;
  const ComplianceReport report = scheduler::build_compliance_report(*db, *id, options);
  const std::string html = render_html(report);

  const std::filesystem::path out = args.out.empty() ? "report-" + id->substr(0, 12) + ".html" : args.out;
  // Written whole or not at all.
  const std::filesystem::path tmp = out.string() + ".partial";
  {
    std::ofstream f(tmp, std::ios::binary | std::ios::trunc);
    if (!f) {
      std::cerr << "error: cannot write " << tmp.string() << '\n';
      return kExitRuntimeFailure;
    }
    f << html;
    if (!f.flush()) {
      std::cerr << "error: cannot write " << tmp.string() << '\n';
      return kExitRuntimeFailure;
    }
  }
  std::filesystem::rename(tmp, out);
  std::cout << "report: " << out.string() << " (" << verdict_name(report.overall) << ")\n";
  return args.fail_on_exceeded ? verdict_exit_code(report.overall) : kExitOk;
}

}  // namespace railvsi::cli
