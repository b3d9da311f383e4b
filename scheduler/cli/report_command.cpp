#include "cli/report_command.hpp"

#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <optional>
#include <string>
#include <string_view>

#include <fmt/format.h>

#include "cli/commands.hpp"
#include "cli/report_pdf.hpp"
#include "cli/service_store.hpp"
#include "cli/verdict_exit.hpp"
#include "core/terminal_text.hpp"
#include "query/compliance_data.hpp"
#include "query/line_table.hpp"
#include "report/compliance_report.hpp"
#include "report/report_json.hpp"
#include "report/report_sections.hpp"
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
  report_->add_option("--out", args_.out, "Report file (default: report-<study id>.html)")
      ->check(CLI::Validator(
          [](const std::string& v) {
            return v.empty() ? std::string("an empty file name; leave --out out for report-<study id>.html")
                             : std::string();
          },
          "FILE"));
  report_->add_flag("!--no-histories", args_.histories, "Do not re-simulate the governing cases");
  report_->add_option("--format", args_.format,
                      "html (default): the report to read and print; json: its content as data (checks, tables, "
                      "figures with the stored value and plotted peak of each governing case), on standard output "
                      "unless --out is given")
      ->check(CLI::IsMember({"html", "json"}));
  report_->add_option("--pdf", args_.pdf,
                      "Print the HTML report to this A4 PDF with headless Chromium, the contents' page numbers "
                      "filled in (printed twice: headings are found with pdftotext); the HTML is written only "
                      "with --out")
      ->check(CLI::Validator(
          [](const std::string& v) { return v.empty() ? std::string("an empty file name") : std::string(); }, "FILE"));
  report_->add_flag("--fail-on-exceeded", args_.fail_on_exceeded, kFailOnExceededHelp);
  report_->footer(verdict_exit_footer(false));
}

std::optional<int> ReportCommand::run_parsed() const {
  if (!report_->parsed()) return std::nullopt;
  return report_command(args_);
}

namespace {

// Why `out` cannot take the report, or nullopt. The report replaces a
// regular file only: renaming onto a device, a FIFO or a symbolic link would
// replace that node (run as root, --out /dev/null replaced the system's).
std::optional<std::string> unusable_out(const std::filesystem::path& out) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::file_status st = fs::symlink_status(out, ec);
  if (fs::exists(st) && !fs::is_regular_file(st))
    return fmt::format("--out {}: it exists and is not a regular file ({}); the report replaces a regular file "
                       "only: give another path",
                       out.string(), fs::is_symlink(st) ? "a symbolic link" : fs::is_directory(st) ? "a directory"
                                                                                                  : "a device or FIFO");
  const fs::path dir = out.parent_path().empty() ? fs::path(".") : out.parent_path();
  if (!fs::is_directory(dir, ec)) return fmt::format("--out {}: its folder {} does not exist", out.string(), dir.string());
  return std::nullopt;
}

// Writes `text` whole or not at all: to a new file beside `out`, made by
// mkstemp (a new name, O_EXCL, so a symbolic link or FIFO planted at a fixed
// OUT.partial is never followed), then renamed onto `out`. On failure the
// temporary file is removed and the reason returned.
std::optional<std::string> write_whole(const std::filesystem::path& out, std::string_view text) {
  std::string tmp = out.string() + ".partial-XXXXXX";
  const int fd = ::mkstemp(tmp.data());
  if (fd < 0) return std::strerror(errno);
  int error = 0;
  ::fchmod(fd, 0644);  // a report is read by others (mkstemp makes 0600)
  for (std::size_t done = 0; done < text.size() && error == 0;) {
    const ssize_t n = ::write(fd, text.data() + done, text.size() - done);
    if (n > 0) done += static_cast<std::size_t>(n);
    else if (n == 0 || errno != EINTR) error = n == 0 ? EIO : errno;
  }
  if (error == 0 && ::fsync(fd) != 0) error = errno;
  if (::close(fd) != 0 && error == 0) error = errno;
  std::error_code ec;
  if (error == 0) {
    std::filesystem::rename(tmp, out, ec);
    if (!ec) return std::nullopt;
  }
  std::error_code ignored;
  std::filesystem::remove(tmp, ignored);
  return error != 0 ? std::string(std::strerror(error)) : ec.message();
}

}  // namespace

int report_command(const ReportArgs& args) {
  if (!args.out.empty())
    if (const auto why = unusable_out(args.out)) {
      std::cerr << "error: " << scheduler::terminal_safe(*why) << '\n';
      return kExitInvalidInput;
    }
  if (!args.pdf.empty()) {
    std::optional<std::string> why;
    if (args.format == "json") why = "--pdf prints the HTML report: it does not go with --format json";
    if (!why) why = pdf_tools_missing();
    if (!why) why = unusable_out(args.pdf);
    if (why) {
      std::cerr << "error: " << scheduler::terminal_safe(*why) << '\n';
      return kExitInvalidInput;
    }
  }
  auto opened = open_study(args.db, args.study_id);
  if (!opened) return kExitInvalidInput;
  const auto& db = opened->db;
  const std::optional<std::string> id = opened->id;
  // A damaged file is reported, never turned into a partial report. A line
  // study is read bridge by bridge (BridgeReader), which refuses a done job
  // without envelopes as it reads: the links alone are checked first.
  const bool line = !scheduler::study_structure_names(*db, *id).empty();
  scheduler::require_consistent_study(*db, *id, line ? scheduler::StudyCheck::kLinks : scheduler::StudyCheck::kAll);
  scheduler::ComplianceOptions options;
  options.version = RAILVSI_VERSION_STRING;
  options.date = report_date();
  options.histories = args.histories;
  ComplianceReport report;
  std::string html;
  std::vector<LineBridge> bridges;
  if (!line) {
    report = scheduler::build_compliance_report(*db, *id, options);
  } else {
    // A line study: the line summary and a section per bridge, each judged over its own jobs.
    bridges = scheduler::line_bridges(*db, *id, options);
    const std::vector<scheduler::JobResult> none;
    options.jobs = &none;  // the study's name, id and inputs only
    report = scheduler::build_compliance_report(*db, *id, options);
    std::vector<CheckResult> all;
    for (const LineBridge& b : bridges) all.insert(all.end(), b.report.checks.begin(), b.report.checks.end());
    report.overall = overall_verdict(all);
    html = render_line_html(report, bridges);
  }
  const bool json = args.format == "json";
  std::string text = json ? (line ? line_report_json(report, bridges) : report_json(report)).dump(2) + "\n"
                     : html.empty() ? render_html(report)
                                    : html;
  if (json && args.out.empty()) {
    std::cout << text;
    return args.fail_on_exceeded ? verdict_exit_code(report.overall) : kExitOk;
  }

  if (!args.pdf.empty()) {
    PdfPrint printed;
    try {
      printed = print_report_pdf(text);
    } catch (const std::exception& e) {
      std::cerr << "error: cannot print " << args.pdf << ": " << scheduler::terminal_safe(e.what())
                << "; nothing was written\n";
      return kExitRuntimeFailure;
    }
    if (const auto why = write_whole(args.pdf, printed.pdf)) {
      std::cerr << "error: cannot write " << args.pdf << " (" << *why << "); nothing was written\n";
      return kExitRuntimeFailure;
    }
    std::cout << fmt::format("report: {} ({} pages, contents numbered in {} prints; {})\n", args.pdf,
                             printed.page_count, printed.passes, verdict_name(report.overall));
    if (args.out.empty()) return args.fail_on_exceeded ? verdict_exit_code(report.overall) : kExitOk;
    text = with_contents_pages(text, printed.pages);  // the HTML as printed
  }
  const std::filesystem::path out = args.out.empty() ? "report-" + id->substr(0, 12) + ".html" : args.out;
  if (const auto why = unusable_out(out)) {  // the default name, or the path changed while the report was built
    std::cerr << "error: " << scheduler::terminal_safe(*why) << '\n';
    return kExitInvalidInput;
  }
  if (const auto why = write_whole(out, text)) {
    std::cerr << "error: cannot write " << out.string() << " (" << *why << "); nothing was written\n";
    return kExitRuntimeFailure;
  }
  std::cout << "report: " << out.string() << " (" << verdict_name(report.overall) << ")\n";
  return args.fail_on_exceeded ? verdict_exit_code(report.overall) : kExitOk;
}

}  // namespace railvsi::cli
