#pragma once
// The compliance report's content as data (vsi report --format json): the
// verdicts, the checks with their cases, the tables and every figure's
// series, the governing-case figures with the stored value each shows and
// the peak of its plotted series. The same ComplianceReport render_html
// draws; nothing here is computed anew.
#include <nlohmann/json.hpp>

#include "report/compliance_report.hpp"

namespace railvsi {

nlohmann::json report_json(const ComplianceReport& report);

}  // namespace railvsi
