#pragma once
// `vsi report`: the compliance report of a study as one self-contained HTML
// file, from the study database alone.
#include <optional>
#include <string>

#include <CLI/CLI.hpp>

#include "cli/command_group.hpp"

namespace railvsi::cli {

struct ReportArgs {
  std::string db = "vsi-results.sqlite";
  std::string study_id;
  std::string out;          // default: report-<first 12 digits of the id>.html
  bool histories = true;    // re-simulate the governing cases
  bool fail_on_exceeded = false;
  std::string format = "html";  // or "json": the content as data, on standard output without --out
  std::string pdf;              // also print the HTML report to this PDF (headless Chromium, two passes)
};

class ReportCommand final : public CommandGroup {
 public:
  explicit ReportCommand(CLI::App& app);
  std::optional<int> run_parsed() const override;

 private:
  ReportArgs args_;
  CLI::App* report_ = nullptr;
};

// Exit 0 (or, with fail_on_exceeded, 4 when a check fails and 5 when one is
// incomplete); 2 for a missing database or study.
int report_command(const ReportArgs& args);

}  // namespace railvsi::cli
