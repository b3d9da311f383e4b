#include "report/compliance_report.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <string_view>

#include <fmt/format.h>

#include "report/report_sections.hpp"

namespace railvsi {
namespace {

constexpr const char* kStyle = R"css(
@page { size: A4; margin: 15mm; }
body { font-family: "DejaVu Sans", "Liberation Sans", Arial, sans-serif; font-size: 10pt; color: #111;
       max-width: 190mm; margin: 0 auto; }
h1 { font-size: 16pt; margin-bottom: 2pt; }
h2 { font-size: 13pt; border-bottom: 1px solid #999; margin-top: 18pt; }
h3 { font-size: 11pt; margin-bottom: 4pt; }
table { border-collapse: collapse; margin: 6pt 0; width: 100%; }
th, td { border: 1px solid #bbb; padding: 2pt 4pt; text-align: left; vertical-align: top; }
th { background: #f0f0f0; }
td.num { text-align: right; font-variant-numeric: tabular-nums; }
.verdict { font-weight: bold; padding: 1pt 4pt; border-radius: 2pt; }
.PASS { background: #d8f0d8; color: #145214; }
.FAIL { background: #f8d0d0; color: #8a1010; }
.INCOMPLETE { background: #fbe8b8; color: #6b4a00; }
.NOT-EVALUATED { background: #e8e8e8; color: #444; }
.overall { font-size: 13pt; margin: 8pt 0; }
.unverified { color: #8a5a00; font-style: italic; }
.estimate-warning { color: #a00000; font-weight: bold; }
figure { margin: 8pt 0; page-break-inside: avoid; break-inside: avoid; }
figcaption { font-size: 9pt; color: #333; }
svg.plot { font-family: inherit; }
svg .plot-title { font-size: 12px; font-weight: bold; }
svg .tick, svg .legend { font-size: 10px; }
svg .axis { font-size: 11px; }
pre { font-size: 8pt; background: #f7f7f7; border: 1px solid #ddd; padding: 4pt; white-space: pre-wrap;
      word-break: break-all; }
.small { font-size: 8.5pt; color: #444; }
)css";

std::string esc(const std::string& s) { return html_escape(s); }

// The dynamic load effect against Phi x LM71 says which governs the design
// (informative), the other checks pass or fail.
std::string verdict_span(const CheckResult& c) {
  if (c.id != "dynamic_enhancement" || c.verdict == Verdict::kIncomplete || c.verdict == Verdict::kNotEvaluated)
    return verdict_html(c.verdict);
  return c.verdict == Verdict::kFail ? "<span class=\"verdict informative\">DYNAMIC GOVERNS</span>"
                                     : "<span class=\"verdict informative\">LM71 GOVERNS</span>";
}

std::string verdict_span_of(Verdict v) { return verdict_html(v); }

std::string value_text(double v) { return fmt::format("{:.4g}", v); }

// The error estimate of a governing value (a study's accuracy.verify),
// flagged when beyond the study's tolerance.
std::string estimate_cell(const CheckResult& c, double tolerance) {
  if (!c.governing || !c.governing->value || !c.governing->error_estimate) return "-";
  const double e = *c.governing->error_estimate;
  std::string text = fmt::format("{:+.2f} %", 100.0 * e);
  if (std::abs(e) > tolerance)
    text += fmt::format(" <span class=\"estimate-warning\">&#9888; above the tolerance {:g} %</span>", 100.0 * tolerance);
  return text;
}

std::string checks_table(const ComplianceReport& r) {
  // The error-estimate column only for a study that verified its governing cases.
  const bool estimates = std::any_of(r.checks.begin(), r.checks.end(), [](const CheckResult& c) {
    return c.governing && c.governing->error_estimate.has_value();
  });
  std::string out =
      "<table class=\"checks\"><tr><th>check</th><th>clause</th><th>limit</th><th>governing value</th>" +
      std::string(estimates ? "<th>error estimate</th>" : "") +
      "<th>train</th><th>km/h</th><th>profile</th><th>cases (missing)</th><th>verdict</th></tr>\n";
  for (const CheckResult& c : r.checks) {
    const std::string limit =
        c.verdict == Verdict::kNotEvaluated && c.limit == 0.0
            ? std::string("-")
            : value_text(c.limit) + " " + esc(c.unit) +
                  (c.limit_verified ? "" : " <span class=\"unverified\">(unverified)</span>");
    std::string gov = "-", train = "-", speed = "-", profile = "-";
    if (c.governing && c.governing->value) {
      gov = value_text(*c.governing->value) + " " + esc(c.unit);
      train = esc(c.governing->train);
      speed = std::isfinite(c.governing->speed_kmh) ? fmt::format("{:g}", c.governing->speed_kmh) : "-";
      const std::string& irregularity = c.governing->irregularity;
      const std::string& point = c.governing->location;
      profile = esc(point.empty() ? irregularity : (irregularity.empty() ? "" : irregularity + ", ") + "point " + point);
      if (!c.governing->variant.empty())
        profile += fmt::format(", <span class=\"bound\">bound: {}</span>", esc(c.governing->variant));
    }
    if (estimates) gov += "</td><td class=\"num estimate\">" + estimate_cell(c, r.accuracy_tolerance);
    out += fmt::format(
        "<tr data-check=\"{}\"><td>{}</td><td>{}</td><td class=\"num\">{}</td><td class=\"num\">{}</td>"
        "<td>{}</td><td class=\"num\">{}</td><td>{}</td><td class=\"num\">{} ({})</td><td>{}</td></tr>\n",
        esc(c.id), esc(c.title), esc(c.clause), limit, gov, train, speed, profile, c.cases, c.missing,
        verdict_span(c));
    if (!c.note.empty())
      out += fmt::format("<tr><td></td><td colspan=\"{}\" class=\"small\">{}</td></tr>\n", estimates ? 9 : 8,
                         esc(c.note));
  }
  return out + "</table>\n";
}

// The study's name for the page footer, as a CSS string.
std::string css_string(const std::string& text) {
  std::string out;
  for (char ch : text)
    if (std::isalnum(static_cast<unsigned char>(ch)) || std::string_view(" .,:;-_()+=/&").find(ch) != std::string_view::npos)
      out += ch;
  return out.size() > 90 ? out.substr(0, 87) + "..." : out;
}

}  // namespace

std::string render_html(const ComplianceReport& r) {
  std::string out = "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n";
  out += "<title>Compliance report: " + esc(r.study_name) + "</title>\n<style>" + std::string(kStyle) +
         kReportPrintStyle + "@page { @bottom-left { content: \"" + css_string(r.title.project) +
         "\"; font-size: 8pt; color: #444; } }\n</style>\n</head>\n<body>\n";
  out += title_block_html(r);
  std::vector<std::pair<std::string, std::string>> sections = {
      {"verdicts", "1. Summary of verdicts"},       {"checks", "2. Checks"},
      {"phi-dyn", "3. Dynamic load effect and phi'dyn"}, {"speed-plots", "4. Other responses against speed"},
      {"histories", "5. Governing cases"},          {"structure", "6. Structure: frequencies and modes"},
      {"model", "7. Model and runs"},                {"code-values", "8. Code values not confirmed in the text"},
      {"inputs", "9. Inputs"}};
  out += contents_html(sections);

  out += "<h2 id=\"verdicts\">1. Summary of verdicts</h2>\n";
  out += "<p class=\"overall\">Overall: " + verdict_span_of(r.overall) + "</p>\n";
  out += "<p class=\"small\">A check FAILS as soon as one case exceeds its limit; it is INCOMPLETE when no case "
         "exceeds but some case has no value (cancelled, failed or not run); it PASSES only when every case has a "
         "value within the limit. Limits marked unverified are explained in section 8.</p>\n";
  out += checks_table(r);
  for (const std::string& n : r.notes) out += "<p class=\"small\">" + esc(n) + "</p>\n";

  out += "<h2 id=\"checks\">2. Checks</h2>\n";
  for (const CheckResult& c : r.checks) {
    if (c.id == "dynamic_enhancement") continue;  // section 3
    const auto plot = std::find_if(r.check_figures.begin(), r.check_figures.end(),
                                   [&](const ReportFigure& f) { return f.check == c.id; });
    out += check_section_html(c, plot == r.check_figures.end() ? nullptr : &*plot);
  }

  out += "<h2 id=\"phi-dyn\">3. Dynamic load effect and phi'dyn</h2>\n" + phi_dyn_html(r);

  out += "<h2 id=\"speed-plots\">4. Other responses against speed</h2>\n";
  if (r.response_figures.empty()) out += "<p>No other stored quantity has a value.</p>\n";
  for (const ReportFigure& f : r.response_figures) out += figure_html(f);

  out += "<h2 id=\"histories\">5. Governing cases</h2>\n";
  out += "<p class=\"small\">Each governing job run again exactly as the worker ran it (its stored scene, rung, time "
         "step, contact law and escalation); each figure names the value the job stored and the peak of what it "
         "plots.</p>\n";
  if (r.governing_cases.empty()) out += "<p>No governing case (no check has a value).</p>\n";
  for (const GoverningCase& g : r.governing_cases) {
    out += "<h3>" + esc(g.heading) + "</h3>\n";
    if (g.status != "ok") out += "<p>Re-run status: <b>" + esc(g.status) + "</b></p>\n";
    for (const ReportFigure& f : g.figures) out += figure_html(f);
  }

  out += "<h2 id=\"structure\">6. Structure: frequencies and modes</h2>\n" + modes_html(r);

  out += "<h2 id=\"model\">7. Model and runs</h2>\n<table class=\"model\">\n";
  for (const ReportRow& row : r.model)
    out += "<tr><th>" + esc(row.key) + "</th><td>" + esc(row.value) + "</td></tr>\n";
  out += "</table>\n<h3>Models and time steps used</h3>\n<table class=\"rungs\"><tr><th>model</th><th>time step and "
         "why</th><th>jobs</th></tr>\n";
  for (const RungGroup& g : r.rungs)
    out += fmt::format("<tr><td>{}</td><td>{}</td><td class=\"num\">{}</td></tr>\n", esc(g.rung), esc(g.dt), g.jobs);
  out += "</table>\n<h3>Jobs without a clean result</h3>\n";
  if (r.issues.empty()) {
    out += "<p>Every job finished with status ok and no warning.</p>\n";
  } else {
    out += "<table class=\"issues\"><tr><th>case</th><th>state</th><th>detail</th></tr>\n";
    for (const JobIssue& i : r.issues)
      out += "<tr><td>" + esc(i.job) + "</td><td>" + esc(i.state) + "</td><td>" + esc(without_file_paths(i.detail)) +
             "</td></tr>\n";
    out += "</table>\n";
  }
  out += "<h3 id=\"accuracy-price\">Accuracy price</h3>\n<p class=\"small\">" + esc(r.price_note) + "</p>\n";
  for (const PriceFigure& f : r.price_charts)
    out += "<figure>\n" + render_price_chart(f.chart) + "<figcaption>" + esc(f.caption) + "</figcaption>\n</figure>\n";

  out += "<h2 id=\"code-values\">8. Code values not confirmed in the text</h2>\n" + unverified_html(r);

  out += "<h2 id=\"inputs\">9. Inputs</h2>\n<h3>Trains</h3>\n<table class=\"trains\"><tr><th>train</th>"
         "<th>source</th></tr>\n";
  for (const LibraryTrain& t : r.trains)
    out += "<tr><td>" + esc(t.name) + "</td><td>" + esc(without_file_paths(t.source)) + "</td></tr>\n";
  out += "</table>\n<h3>Study document</h3>\n<p class=\"small\">Its id is the SHA-256 of this canonical "
         "document.</p>\n<pre>" + esc(without_file_paths(r.study_document)) + "</pre>\n";
  out += "</body>\n</html>\n";
  return out;
}

}  // namespace railvsi
