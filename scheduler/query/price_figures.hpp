#pragma once
// The accuracy-price charts of a study's report, from the price rows
// `vsi price --db F --study ID` stored (query/price_rows): one chart per
// priced job and quantity that has errors; or the one line saying how to
// get them.
#include <string>

#include "report/compliance_report.hpp"
#include "store/sqlite.hpp"

namespace railvsi::scheduler {

void add_price_figures(Database& db, const std::string& study_id, ComplianceReport& report);

}  // namespace railvsi::scheduler
