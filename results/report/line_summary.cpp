#include "report/line_summary.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "report/line_plot.hpp"

namespace railvsi {
namespace {

constexpr const char* kLineStyle = R"css(
body { font-family: sans-serif; font-size: 10pt; max-width: 180mm; margin: auto; }
table { border-collapse: collapse; margin: 6pt 0; }
th, td { border: 1px solid #999; padding: 2pt 4pt; text-align: left; vertical-align: top; }
td.num { text-align: right; }
.verdict { font-weight: bold; padding: 0 3pt; }
.PASS { color: #005a00; } .FAIL { color: #b00000; } .INCOMPLETE, .NOT-EVALUATED { color: #8a5a00; }
.small { font-size: 8.5pt; color: #444; }
figure { margin: 8pt 0; page-break-inside: avoid; break-inside: avoid; }
section.bridge { page-break-before: always; break-before: page; }
@page { size: A4; margin: 15mm; }
)css";

std::string esc(const std::string& s) { return html_escape(s); }

std::string verdict_span(Verdict v) {
  std::string cls = verdict_name(v);
  std::replace(cls.begin(), cls.end(), ' ', '-');
  return fmt::format("<span class=\"verdict {}\">{}</span>", cls, verdict_name(v));
}

int rank(Verdict v) {
  switch (v) {
    case Verdict::kFail: return 0;
    case Verdict::kIncomplete: return 1;
    case Verdict::kNotEvaluated: return 2;
    case Verdict::kPass: return 3;
  }
  return 2;
}

// "0.812 m/s2 (limit 3.5), HSLM-A3 at 301 km/h" or "-".
std::string governing_cell(const CheckResult& c) {
  if (!c.governing || !c.governing->value) return "-";
  std::string text = fmt::format("{:.4g} {} (limit {:.4g})", *c.governing->value, esc(c.unit), c.limit);
  if (std::isfinite(c.governing->speed_kmh) && c.governing->speed_kmh > 0.0)  // a static check (LM71) has no speed
    text += fmt::format("<br><span class=\"small\">{} at {:g} km/h</span>", esc(c.governing->train),
                        c.governing->speed_kmh);
  return text;
}

std::string anchor(std::size_t k) { return fmt::format("bridge-{}", k + 1); }

}  // namespace

std::vector<const LineBridge*> failing_first(const std::vector<LineBridge>& bridges) {
  std::vector<const LineBridge*> order;
  for (const LineBridge& b : bridges) order.push_back(&b);
  std::stable_sort(order.begin(), order.end(), [](const LineBridge* a, const LineBridge* b) {
    return rank(a->report.overall) < rank(b->report.overall);
  });
  return order;
}

std::string render_line_html(const ComplianceReport& line, const std::vector<LineBridge>& bridges) {
  std::string out = "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n";
  out += "<title>Line report: " + esc(line.study_name) + "</title>\n<style>" + std::string(kLineStyle) +
         "</style>\n</head>\n<body>\n";
  out += "<h1>Dynamic analysis of the bridges of a line: compliance report</h1>\n";
  out += fmt::format("<p>Study <b>{}</b> <span class=\"small\">({})</span>, {} bridges<br>railvsi {}<br>"
                     "<span class=\"small\" id=\"date\">Generated {}</span></p>\n",
                     esc(line.study_name), esc(line.study_id), bridges.size(), esc(line.version), esc(line.date));

  // The checks named in the columns: those of any bridge, in the order of the first that has them.
  std::vector<std::pair<std::string, std::string>> columns;  // id, title
  for (const LineBridge& b : bridges)
    for (const CheckResult& c : b.report.checks)
      if (std::none_of(columns.begin(), columns.end(), [&](const auto& col) { return col.first == c.id; }))
        columns.emplace_back(c.id, c.title);
  int failing = 0;
  for (const LineBridge& b : bridges) failing += b.report.overall == Verdict::kFail;
  out += "<h2 id=\"line-summary\">1. Line summary</h2>\n";
  out += fmt::format("<p>{} of {} bridges fail a check. One row per bridge, failing ones first; per check its "
                     "verdict, governing value and the train and speed that govern it.</p>\n",
                     failing, bridges.size());
  out += "<table class=\"line\"><tr><th>bridge</th><th>verdict</th>";
  for (const auto& col : columns) out += "<th>" + esc(col.second) + "</th>";
  out += "</tr>\n";
  for (const LineBridge* b : failing_first(bridges)) {
    const auto k = static_cast<std::size_t>(b - bridges.data());
    out += fmt::format("<tr><td><a href=\"#{}\">{}</a></td><td>{}</td>", anchor(k), esc(b->name),
                       verdict_span(b->report.overall));
    for (const auto& col : columns) {
      const auto c = std::find_if(b->report.checks.begin(), b->report.checks.end(),
                                  [&](const CheckResult& r) { return r.id == col.first; });
      out += c == b->report.checks.end() ? std::string("<td>-</td>")
                                         : "<td>" + verdict_span(c->verdict) + " " + governing_cell(*c) + "</td>";
    }
    out += "</tr>\n";
  }
  out += "</table>\n";

  out += "<h2 id=\"bridges\">2. Bridges</h2>\n";
  for (std::size_t k = 0; k < bridges.size(); ++k) {
    const ComplianceReport& r = bridges[k].report;
    out += fmt::format("<section class=\"bridge\"><h3 id=\"{}\">2.{} {}</h3>\n<p>Overall: {}</p>\n", anchor(k), k + 1,
                       esc(bridges[k].name), verdict_span(r.overall));
    out += "<table class=\"checks\"><tr><th>check</th><th>clause</th><th>governing value, case</th><th>cases</th>"
           "<th>missing</th><th>verdict</th></tr>\n";
    for (const CheckResult& c : r.checks)
      out += fmt::format("<tr><td>{}</td><td>{}</td><td>{}</td><td class=\"num\">{}</td><td class=\"num\">{}</td>"
                         "<td>{}</td></tr>\n",
                         esc(c.title), esc(c.clause), governing_cell(c), c.cases, c.missing, verdict_span(c.verdict));
    out += "</table>\n";
    for (const std::string& n : r.notes) out += "<p class=\"small\">" + esc(n) + "</p>\n";
    const auto figure = [](const ReportFigure& f) {
      return "<figure>\n" + render_svg(f.plot) + "<figcaption>" + esc(f.caption) + "</figcaption>\n</figure>\n";
    };
    for (const ReportFigure& f : r.check_figures) out += figure(f);
    // The governing cases re-run (vsi report without --no-histories).
    for (const GoverningCase& g : r.governing_cases) {
      out += "<h4>" + esc(g.heading) + "</h4>\n";
      if (g.status != "ok") out += "<p>Re-run status: <b>" + esc(g.status) + "</b></p>\n";
      for (const ReportFigure& f : g.figures) out += figure(f);
    }
    out += "<table class=\"model\">\n";
    for (const ReportRow& row : r.model) out += "<tr><th>" + esc(row.key) + "</th><td>" + esc(row.value) + "</td></tr>\n";
    out += "</table>\n</section>\n";
  }
  out += "<h2 id=\"inputs\">3. Inputs</h2>\n<pre class=\"small\">" + esc(line.study_document) + "</pre>\n";
  out += "</body>\n</html>\n";
  return out;
}

}  // namespace railvsi
