#pragma once
// The report of a line study (a study with "structures"): one file with the
// line summary (one row per bridge, failing ones first: its verdict and,
// per check, the governing value, train and speed) and a section per bridge
// (its checks, its response against speed, its governing cases re-run when
// the reports have them, and its model). Each bridge's
// content is the compliance report of its jobs alone.
#include <string>
#include <vector>

#include "report/compliance_report.hpp"

namespace railvsi {

struct LineBridge {
  std::string name;
  ComplianceReport report;  // the bridge's own: its checks, figures and model
};

// The order of the line summary: FAIL, then INCOMPLETE or NOT EVALUATED,
// then PASS; the study's order within each.
std::vector<const LineBridge*> failing_first(const std::vector<LineBridge>& bridges);

// The whole document; `line` gives the study's name, id, version, date and
// inputs (its checks are not used).
std::string render_line_html(const ComplianceReport& line, const std::vector<LineBridge>& bridges);

}  // namespace railvsi
