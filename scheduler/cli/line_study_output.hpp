#pragma once
// What vsi query and vsi run print for a whole line study, read bridge by
// bridge (BridgeReader): one bridge's jobs in memory at a time, so a line
// of 900,000 jobs prints in the memory of one bridge's 3,000.
#include <optional>
#include <ostream>
#include <string>

#include "compliance/check_verdict.hpp"
#include "query/study_results.hpp"
#include "store/sqlite.hpp"

namespace railvsi::cli {

struct LineStudyOutputOptions {
  // "table": each bridge's table as vsi query --structure NAME prints it,
  // one after the other; "csv": the CSV of the whole study (the same bytes
  // as one read of every job: the bridges in the study's order).
  std::string format = "table";
  // Judge each bridge (as vsi query --line does) and print its verdict
  // lines after its table; the overall verdict is returned.
  bool judge = false;
};

// Returns the overall verdict of every bridge's checks when options.judge.
std::optional<Verdict> write_line_study_by_bridge(scheduler::Database& db, const scheduler::StudyInfo& info,
                                                  const LineStudyOutputOptions& options, std::ostream& out);

// vsi run's last output for a line study: the line table (a row per bridge),
// and the overall verdict of every bridge's checks.
Verdict write_line_table(scheduler::Database& db, const std::string& study_id, std::ostream& out);

}  // namespace railvsi::cli
