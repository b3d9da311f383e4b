#pragma once
// The compliance report's content as data (vsi report --format json): the
// verdicts, the checks with their cases, the tables and every figure's
// series, the governing-case figures with the stored value each shows and
// the peak of its plotted series. The same ComplianceReport render_html
// draws; nothing here is computed anew.
#include <nlohmann/json.hpp>

#include <vector>

#include "report/compliance_report.hpp"
#include "report/line_summary.hpp"

namespace railvsi {

nlohmann::json report_json(const ComplianceReport& report);

// A line study's: the line's (its overall checks, judged over every
// bridge) and "structures", one per bridge in the study's order with its
// own checks (each with its table per train), figures, governing cases and
// model, as the HTML's section per bridge.
nlohmann::json line_report_json(const ComplianceReport& line, const std::vector<LineBridge>& bridges);

}  // namespace railvsi
