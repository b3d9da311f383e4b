#pragma once
// Sections of the compliance report's HTML (render_html assembles them):
// the title block and contents, one section per check (a table per train
// and its plot against speed), phi'dyn as a table, the structure's modes,
// the values not confirmed in the standard's text. And the print style:
// A4 pages numbered "page n of N" by CSS @page counters.
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "report/compliance_report.hpp"

namespace railvsi {

// The print rules (@page margin boxes, page breaks) added to the screen style.
extern const char* const kReportPrintStyle;

std::string verdict_html(Verdict v);
std::string figure_html(const ReportFigure& f);

std::string title_block_html(const ComplianceReport& r);
// (anchor id, title) of each numbered section, in order.
// Each entry has an empty page number, filled by with_contents_pages once
// the report is printed (Chromium has no CSS target-counter).
std::string contents_html(const std::vector<std::pair<std::string, std::string>>& sections);
// The contents entries of a report's HTML: (section id, title as printed).
std::vector<std::pair<std::string, std::string>> contents_entries(const std::string& html);
// The HTML with the page number of each entry in `pages` (by section id).
std::string with_contents_pages(const std::string& html, const std::map<std::string, int>& pages);
// One check: clause, limit, note, the table per train, its plot (null: none).
std::string check_section_html(const CheckResult& c, const ReportFigure* plot);
// The dynamic load effect against Phi x LM71 (informative: which governs)
// and phi'dyn per train and load effect.
std::string phi_dyn_html(const ComplianceReport& r);
std::string modes_html(const ComplianceReport& r);
std::string unverified_html(const ComplianceReport& r);

// A source text without file paths: a path of this repository becomes
// "railvsi's source" or "railvsi's test suite", an absolute path "a file
// given with the study".
std::string without_file_paths(const std::string& text);

}  // namespace railvsi
