#include "report/report_sections.hpp"

#include <cmath>
#include <regex>

#include <fmt/format.h>

namespace railvsi {

// Chromium prints @page margin boxes (since version 131): the page number
// and count in the footer, the study in the header; sections start on a new
// page, figures and table rows are not split.
const char* const kReportPrintStyle = R"css(
@page { size: A4; margin: 18mm 15mm 20mm 15mm;
  @bottom-right { content: "page " counter(page) " of " counter(pages); font-size: 8pt; color: #444; } }
.title-block { border: 1.5px solid #333; padding: 6pt 8pt; margin-bottom: 10pt; box-sizing: border-box;
  margin-right: 2px; }  /* at the content's very edge Chromium's print left the right border out */
.title-block table { margin: 4pt 0 0 0; }
.title-block th { width: 28%; }
.sign td { height: 22pt; }
nav.contents ol { margin: 4pt 0 0 0; padding: 0; list-style: none; }
nav.contents li { margin: 1pt 0; display: flex; max-width: 120mm; }
nav.contents li .entry { flex: 1; }
nav.contents li .page { min-width: 3em; text-align: right; }
section.check { break-inside: auto; }
table.per-train td.verdict-cell { white-space: nowrap; }
.informative { background: #e8eef8; color: #1d3d6b; }
@media print {
  body { max-width: none; margin: 0; }
  h2 { break-before: page; break-after: avoid; }
  h2.first { break-before: auto; }
  h3 { break-after: avoid; }
  tr, figure { break-inside: avoid; }
  pre { font-size: 7pt; }
}
)css";

namespace {

std::string esc(const std::string& s) { return html_escape(s); }

std::string number(double v) { return fmt::format("{:.4g}", v); }

}  // namespace

std::string verdict_html(Verdict v) {
  std::string cls = verdict_name(v);
  for (char& c : cls)
    if (c == ' ') c = '-';
  return fmt::format("<span class=\"verdict {}\">{}</span>", cls, verdict_name(v));
}

std::string figure_html(const ReportFigure& f) {
  return "<figure>\n" + render_svg(f.plot) + "<figcaption>" + esc(f.caption) + "</figcaption>\n</figure>\n";
}

std::string title_block_html(const ComplianceReport& r) {
  std::string out = "<header class=\"title-block\">\n<h1>" + esc(r.title.project) + "</h1>\n";
  out += "<p>Dynamic analysis of a railway bridge under high-speed trains: compliance report (EN 1990 A2, "
         "EN 1991-2 6.4)</p>\n<table class=\"title\">\n";
  const auto row = [&](const char* key, const std::string& value, const char* cls = "") {
    out += fmt::format("<tr{}><th>{}</th><td>{}</td></tr>\n", cls, key, value);
  };
  row("Project", esc(r.title.project));
  row("Structure", esc(r.title.structure.empty() ? std::string("see section Model") : r.title.structure));
  row("Study", esc(r.study_name) + "<br><span class=\"small\">id " + esc(r.study_id) + "</span>");
  row("Tool", "railvsi " + esc(r.version));
  row("Date", "<span class=\"small\" id=\"date\">Generated " + esc(r.date) + "</span>");
  row("Overall verdict", verdict_html(r.overall));
  row("Prepared by", esc(r.title.author), " class=\"sign\"");
  row("Checked by", "", " class=\"sign\"");
  out += "</table>\n</header>\n";
  return out;
}

std::string contents_html(const std::vector<std::pair<std::string, std::string>>& sections) {
  std::string out = "<nav class=\"contents\"><h2 class=\"first\" id=\"contents\">Contents</h2>\n<ol>\n";
  for (const auto& [id, title] : sections)
    out += "<li data-section=\"" + esc(id) + "\"><span class=\"entry\">" + esc(title) +
           "</span><span class=\"page\" data-page-of=\"" + esc(id) + "\"></span></li>\n";
  return out + "</ol>\n<p class=\"small\">Page numbers are printed at the foot of each page.</p></nav>\n";
}

namespace {

std::string unescape(std::string s) {
  for (const auto& [from, to] : {std::pair{"&lt;", "<"}, std::pair{"&gt;", ">"}, std::pair{"&quot;", "\""},
                                 std::pair{"&#39;", "'"}, std::pair{"&amp;", "&"}})
    for (std::size_t at = 0; (at = s.find(from, at)) != std::string::npos; at += std::string_view(to).size())
      s.replace(at, std::string_view(from).size(), to);
  return s;
}

}  // namespace

std::vector<std::pair<std::string, std::string>> contents_entries(const std::string& html) {
  static const std::regex entry(R"re(<li data-section="([^"]*)"><span class="entry">([^<]*)</span>)re");
  std::vector<std::pair<std::string, std::string>> out;
  for (auto it = std::sregex_iterator(html.begin(), html.end(), entry); it != std::sregex_iterator(); ++it)
    out.emplace_back(unescape((*it)[1]), unescape((*it)[2]));
  return out;
}

std::string with_contents_pages(const std::string& html, const std::map<std::string, int>& pages) {
  std::string out = html;
  for (const auto& [id, page] : pages) {
    const std::string open = "<span class=\"page\" data-page-of=\"" + esc(id) + "\">";
    const std::size_t at = out.find(open);
    if (at == std::string::npos) continue;
    const std::size_t end = out.find("</span>", at + open.size());
    out.replace(at + open.size(), end - at - open.size(), std::to_string(page));
  }
  return out;
}

std::string check_section_html(const CheckResult& c, const ReportFigure* plot) {
  std::string out = fmt::format("<section class=\"check\" data-check=\"{}\">\n<h3>{} {}</h3>\n", esc(c.id),
                                esc(c.title), verdict_html(c.verdict));
  out += "<p class=\"small\">" + esc(c.clause);
  if (c.verdict != Verdict::kNotEvaluated || c.limit != 0.0)
    out += fmt::format("; limit {} {}{}", number(c.limit), esc(c.unit), c.limit_verified ? "" : " (unverified: see "
                                                                                                "Code values)");
  out += fmt::format(". {} cases, {} without a value.</p>\n", c.cases, c.missing);
  if (!c.note.empty()) out += "<p class=\"small\">" + esc(c.note) + "</p>\n";
  const std::vector<CheckResult> trains = per_train(c);
  if (!trains.empty()) {
    out += "<table class=\"per-train\"><tr><th>train</th><th>governing value</th><th>speed [km/h]</th>"
           "<th>profile / location</th><th>limit</th><th>utilisation</th><th>verdict</th></tr>\n";
    for (const CheckResult& t : trains) {
      const std::string name = t.all_cases.empty() ? std::string() : t.all_cases.front().train;
      std::string value = "-", speed = "-", where = "-", use = "-";
      if (t.governing && t.governing->value) {
        value = number(*t.governing->value) + " " + esc(c.unit);
        speed = std::isfinite(t.governing->speed_kmh) ? fmt::format("{:g}", t.governing->speed_kmh) : "-";
        const std::string& p = t.governing->irregularity;
        const std::string& loc = t.governing->location;
        where = esc(loc.empty() ? (p.empty() ? "-" : p) : (p.empty() ? "" : p + ", ") + loc);
        if (c.limit > 0.0) use = fmt::format("{:.0f} %", 100.0 * *t.governing->value / c.limit);
      }
      out += fmt::format("<tr><td>{}</td><td class=\"num\">{}</td><td class=\"num\">{}</td><td>{}</td>"
                         "<td class=\"num\">{} {}</td><td class=\"num\">{}</td><td class=\"verdict-cell\">{}</td></tr>\n",
                         esc(name), value, speed, where, number(c.limit), esc(c.unit), use, verdict_html(t.verdict));
    }
    out += "</table>\n";
  }
  if (plot) out += figure_html(*plot);
  return out + "</section>\n";
}

std::string phi_dyn_html(const ComplianceReport& r) {
  std::string out;
  for (const CheckResult& c : r.checks) {
    if (c.id != "dynamic_enhancement") continue;
    out += "<h3>" + esc(c.title) + "</h3>\n<p class=\"small\">" + esc(c.clause) +
           ": the design load effect is the more unfavourable of the dynamic one, (1 + phi'dyn + phi''/2) x static, "
           "and Phi x alpha x LM71. A ratio above 1 says the dynamic analysis governs the design, not that the "
           "bridge fails; it is not part of the overall verdict.</p>\n";
    if (!c.note.empty()) out += "<p class=\"small\">" + esc(c.note) + "</p>\n";
    out += "<table class=\"dynamic-enhancement\"><tr><th>train</th><th>ratio to Phi alpha LM71</th><th>speed "
           "[km/h]</th><th>location</th><th>governs</th></tr>\n";
    for (const CheckCase& k : c.all_cases) {
      std::string governs = "no value";
      if (k.value) governs = *k.value > 1.0 ? "dynamic analysis" : "Phi x alpha x LM71";
      out += fmt::format("<tr><td>{}</td><td class=\"num\">{}</td><td class=\"num\">{}</td><td>{}</td>"
                         "<td><span class=\"verdict informative\">{}</span></td></tr>\n",
                         esc(k.train), k.value ? number(*k.value) : "-",
                         k.value && std::isfinite(k.speed_kmh) ? fmt::format("{:g}", k.speed_kmh) : "-",
                         esc(k.location), governs);
    }
    out += "</table>\n";
  }
  if (r.phi_dyn.empty()) return out + "<p>No phi'dyn: no static value of the load effects (see notes).</p>\n";
  out += "<h3>phi'dyn per train and load effect (EN 1991-2 6.4.6.5)</h3>\n<p class=\"small\">phi'dyn = dynamic / "
         "static - 1, the dynamic value the largest over the train's jobs (speed of that job), the static one of the "
         "same train's axle loads on the same structure.</p>\n";
  out += "<table class=\"phi-dyn\"><tr><th>train</th><th>load effect</th><th>location</th><th>static</th>"
         "<th>dynamic</th><th>speed [km/h]</th><th>phi'dyn</th></tr>\n";
  for (const PhiDynRow& p : r.phi_dyn)
    out += fmt::format("<tr><td>{}</td><td>{}</td><td>{}</td><td class=\"num\">{} {}</td><td class=\"num\">{}</td>"
                       "<td class=\"num\">{}</td><td class=\"num\">{}</td></tr>\n",
                       esc(p.train), esc(p.quantity), esc(p.location), number(p.static_value), esc(p.unit),
                       p.dynamic_value ? number(*p.dynamic_value) + " " + esc(p.unit) : "-",
                       p.dynamic_value ? fmt::format("{:g}", p.speed_kmh) : "-", p.phi_dyn ? number(*p.phi_dyn) : "-");
  out += "</table>\n";
  for (const ReportFigure& f : r.phi_dyn_figures) out += figure_html(f);
  return out;
}

std::string modes_html(const ComplianceReport& r) {
  std::string out;
  if (!r.modes_note.empty()) out += "<p>Modes the runs used: " + esc(r.modes_note) + ".</p>\n";
  if (r.mode_shapes) out += figure_html(*r.mode_shapes);
  if (r.modes.empty()) return out + "<p>The structure's modes were not computed.</p>\n";
  out += "<table class=\"modes\"><tr><th>mode</th><th>frequency [Hz]</th><th>role</th></tr>\n";
  for (const ModeRow& m : r.modes)
    out += fmt::format("<tr><td class=\"num\">{}</td><td class=\"num\">{}</td><td>{}</td></tr>\n", m.number,
                       number(m.frequency_hz),
                       m.role == "f0"   ? "f0, first deck bending mode"
                       : m.role == "f3" ? "f3, third mode of the member (the code filter's cut-off)"
                                        : "");
  return out + "</table>\n<p class=\"small\">The lowest modes of the whole structure (deck and track), from the "
               "modal analysis of the study's structure model.</p>\n";
}

std::string unverified_html(const ComplianceReport& r) {
  if (r.unverified.empty()) return "<p>Every code value used was read in the standard's text.</p>\n";
  std::string out = "<ul class=\"unverified-list\">\n";
  for (const std::string& u : r.unverified) out += "<li>" + esc(u) + "</li>\n";
  return out + "</ul>\n";
}

std::string without_file_paths(const std::string& text) {
  static const std::regex repository(R"(\b(engine|results|scheduler|jobs)/[\w./-]*[\w])");
  static const std::regex tests(R"(\btests/[\w./-]*[\w])");
  static const std::regex absolute(R"((^|[\s(])/(?:[\w.-]+/)+[\w.-]+)");
  std::string out = std::regex_replace(text, repository, "railvsi's source");
  out = std::regex_replace(out, tests, "railvsi's test suite");
  return std::regex_replace(out, absolute, "$1a file given with the study");
}

}  // namespace railvsi
