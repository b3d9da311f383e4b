#include "report/report_json.hpp"

#include <cmath>

namespace railvsi {
namespace {

using nlohmann::json;

json optional_number(const std::optional<double>& v) { return v ? json(*v) : json(nullptr); }

json case_json(const CheckCase& c) {
  json j = {{"train", c.train},       {"speed_kmh", c.speed_kmh}, {"profile", c.irregularity},
            {"value", optional_number(c.value)}, {"job", c.job_id},      {"location", c.location}};
  if (!c.variant.empty()) j["variant"] = c.variant;
  if (c.error_estimate) j["error_estimate"] = *c.error_estimate;
  return j;
}

json plot_json(const LinePlot& p) {
  json series = json::array();
  for (const PlotSeries& s : p.series) {
    json points = json::array();
    for (const auto& [x, y] : s.points) points.push_back({x, std::isfinite(y) ? json(y) : json(nullptr)});
    series.push_back({{"label", s.label}, {"points", points}});
  }
  json j = {{"title", p.title}, {"x_label", p.x_label}, {"y_label", p.y_label}, {"series", series}};
  if (p.limit) j["limit"] = *p.limit;
  if (p.marked) j["marked"] = {p.marked->first, p.marked->second};
  if (!p.x_marks.empty()) j["x_marks"] = {{"label", p.x_marks_label}, {"x", p.x_marks}};
  if (p.shaded_x) j["shaded_x"] = {{"label", p.shaded_label}, {"x", {p.shaded_x->first, p.shaded_x->second}}};
  return j;
}

json figure_json(const ReportFigure& f) {
  json j = {{"caption", f.caption}, {"plot", plot_json(f.plot)}};
  if (f.data) {
    const FigureData& d = *f.data;
    j["quantity"] = d.quantity;
    j["location"] = d.location;
    j["job"] = d.job;
    j["stored_value"] = optional_number(d.stored_value);
    j["plotted_peak"] = d.plotted_peak;
    j["min"] = d.min;
    j["max"] = d.max;
    j["window_s"] = {d.window_s.first, d.window_s.second};
    if (d.unilateral) j["unilateral"] = *d.unilateral;
  }
  return j;
}

json rows_json(const std::vector<ReportRow>& rows) {
  json out = json::array();
  for (const ReportRow& r : rows) out.push_back({{"key", r.key}, {"value", r.value}});
  return out;
}

// The checks, each with its table per train and all its cases.
json checks_json(const ComplianceReport& r) {
  json checks = json::array();
  for (const CheckResult& c : r.checks) {
    json cases = json::array();
    for (const CheckCase& k : c.all_cases) cases.push_back(case_json(k));
    json trains = json::array();
    for (const CheckResult& t : per_train(c))
      trains.push_back({{"train", t.all_cases.empty() ? std::string() : t.all_cases.front().train},
                        {"verdict", verdict_name(t.verdict)},
                        {"governing", t.governing ? case_json(*t.governing) : json(nullptr)},
                        {"cases", t.cases},
                        {"missing", t.missing}});
    checks.push_back({{"id", c.id},
                      {"title", c.title},
                      {"clause", c.clause},
                      {"quantity", c.quantity},
                      {"unit", c.unit},
                      {"limit", c.limit},
                      {"limit_verified", c.limit_verified},
                      {"verdict", verdict_name(c.verdict)},
                      {"governing", c.governing ? case_json(*c.governing) : json(nullptr)},
                      {"cases", c.cases},
                      {"missing", c.missing},
                      {"note", c.note},
                      {"per_train", trains},
                      {"all_cases", cases}});
  }
  return checks;
}

json governing_json(const ComplianceReport& r) {
  json governing = json::array();
  for (const GoverningCase& g : r.governing_cases) {
    json figures = json::array();
    for (const ReportFigure& f : g.figures) figures.push_back(figure_json(f));
    governing.push_back({{"heading", g.heading}, {"status", g.status}, {"figures", figures}});
  }
  return governing;
}

json figures_json(const std::vector<ReportFigure>& figures) {
  json out = json::array();
  for (const ReportFigure& f : figures) out.push_back(figure_json(f));
  return out;
}

}  // namespace

json report_json(const ComplianceReport& r) {
  const json checks = checks_json(r);
  const json check_figures = figures_json(r.check_figures);
  const json governing = governing_json(r);
  json rungs = json::array();
  for (const RungGroup& g : r.rungs) rungs.push_back({{"rung", g.rung}, {"dt", g.dt}, {"jobs", g.jobs}});
  json issues = json::array();
  for (const JobIssue& i : r.issues) issues.push_back({{"job", i.job}, {"state", i.state}, {"detail", i.detail}});
  json trains = json::array();
  for (const LibraryTrain& t : r.trains) trains.push_back({{"name", t.name}, {"source", t.source}});
  const json response = figures_json(r.response_figures);
  json phi_dyn = json::array();
  for (const PhiDynRow& p : r.phi_dyn)
    phi_dyn.push_back({{"train", p.train},
                       {"quantity", p.quantity},
                       {"location", p.location},
                       {"unit", p.unit},
                       {"static", p.static_value},
                       {"dynamic", optional_number(p.dynamic_value)},
                       {"speed_kmh", p.speed_kmh},
                       {"phi_dyn", optional_number(p.phi_dyn)}});
  const json phi_dyn_figures = figures_json(r.phi_dyn_figures);
  json modes = json::array();
  for (const ModeRow& m : r.modes) modes.push_back({{"mode", m.number}, {"frequency_hz", m.frequency_hz}, {"role", m.role}});
  return {{"study", {{"name", r.study_name}, {"id", r.study_id}}},
          {"title", {{"project", r.title.project}, {"structure", r.title.structure}, {"author", r.title.author}}},
          {"response_figures", response},
          {"phi_dyn", phi_dyn},
          {"phi_dyn_figures", phi_dyn_figures},
          {"modes", modes},
          {"modes_used", r.modes_note},
          {"mode_shapes", r.mode_shapes ? figure_json(*r.mode_shapes) : json(nullptr)},
          {"unverified", r.unverified},
          {"version", r.version},
          {"date", r.date},
          {"overall", verdict_name(r.overall)},
          {"checks", checks},
          {"check_figures", check_figures},
          {"governing_cases", governing},
          {"model", rows_json(r.model)},
          {"rungs", rungs},
          {"issues", issues},
          {"trains", trains},
          {"notes", r.notes}};
}

json line_report_json(const ComplianceReport& line, const std::vector<LineBridge>& bridges) {
  json out = report_json(line);
  json structures = json::array();
  for (const LineBridge& b : bridges)
    structures.push_back({{"name", b.name},
                          {"overall", verdict_name(b.report.overall)},
                          {"checks", checks_json(b.report)},
                          {"check_figures", figures_json(b.report.check_figures)},
                          {"governing_cases", governing_json(b.report)},
                          {"model", rows_json(b.report.model)},
                          {"notes", b.report.notes}});
  out["structures"] = structures;
  return out;
}

}  // namespace railvsi
