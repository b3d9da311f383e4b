#include "query/line_table.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>

#include <fmt/format.h>

#include "core/terminal_text.hpp"
#include "query/study_report.hpp"

namespace railvsi::scheduler {
namespace {

const CheckCase* governing_case(const CheckResult& c) {
  return c.governing && c.governing->value ? &*c.governing : nullptr;
}

// A static check (LM71) has no speed.
bool has_speed(const CheckCase* g) { return g && std::isfinite(g->speed_kmh) && g->speed_kmh > 0.0; }

}  // namespace

std::vector<LineBridge> line_bridges(Database& db, const std::string& study_id, std::vector<JobResult> jobs,
                                     ComplianceOptions options) {
  std::vector<std::string> names;
  std::map<std::string, std::vector<JobResult>> of_bridge;
  for (JobResult& j : jobs) {
    if (j.structure.empty()) continue;
    auto [it, fresh] = of_bridge.try_emplace(j.structure);
    if (fresh) names.push_back(j.structure);
    it->second.push_back(std::move(j));
  }
  jobs = {};
  std::vector<LineBridge> out;
  for (const std::string& name : names) {
    auto bridge = of_bridge.extract(name);
    options.jobs = &bridge.mapped();
    out.push_back({name, build_compliance_report(db, study_id, options)});
  }
  return out;
}

std::vector<LineBridge> line_bridges(Database& db, const std::string& study_id, ComplianceOptions options) {
  BridgeReader reader(db, study_id, options.checks_only ? BridgeFields::kVerdicts : BridgeFields::kAll);
  std::vector<LineBridge> out;
  std::string name;
  std::vector<JobResult> jobs;
  while (reader.next(name, jobs)) {
    options.jobs = &jobs;
    out.push_back({name, build_compliance_report(db, study_id, options)});
    // The line table reads each check's verdict and governing case, not the
    // case of every job: let them go with the bridge's jobs. (`all_cases =
    // {}` kept their buffer, 200 B a job for each check with a case per job:
    // the peak memory grew by about 0.2 MB a bridge.)
    if (options.checks_only)
      for (CheckResult& c : out.back().report.checks) std::vector<CheckCase>().swap(c.all_cases);
  }
  return out;
}

std::string format_line_table(const std::vector<LineBridge>& bridges) {
  std::size_t name_w = 6;
  for (const LineBridge& b : bridges) name_w = std::max(name_w, terminal_safe(b.name).size());
  std::string out;
  int failing = 0;
  for (const LineBridge& b : bridges) failing += b.report.overall == Verdict::kFail;
  out += fmt::format("line: {} bridges, {} failing\n", bridges.size(), failing);
  out += fmt::format("{:<{}}  {:<13}  {}\n", "bridge", name_w, "verdict", "per check: verdict, governing value, train at speed");
  for (const LineBridge& b : bridges) {
    std::string checks;
    for (const CheckResult& c : b.report.checks) {
      if (c.verdict == Verdict::kNotEvaluated) continue;
      const CheckCase* g = governing_case(c);
      checks += fmt::format("{}{} {}", checks.empty() ? "" : "; ", c.id, verdict_name(c.verdict));
      if (g) {
        checks += fmt::format(" {:.4g}/{:.4g}{}{}", *g->value, c.limit, c.unit.empty() ? "" : " ", c.unit);
        if (has_speed(g))
          checks += fmt::format(" ({} at {:g} km/h)", terminal_safe(g->train), g->speed_kmh);
      }
    }
    out += fmt::format("{:<{}}  {:<13}  {}\n", terminal_safe(b.name), name_w, verdict_name(b.report.overall), checks);
  }
  return out;
}

std::string format_line_csv(const std::vector<LineBridge>& bridges) {
  std::string out = "structure,check,verdict,value,limit,unit,train,speed_kmh,location\n";
  for (const LineBridge& b : bridges)
    for (const CheckResult& c : b.report.checks) {
      const CheckCase* g = governing_case(c);
      out += fmt::format("{},{},{},{},{},{},{},{},{}\n", csv_field(b.name), c.id, verdict_name(c.verdict),
                         g ? fmt::format("{}", *g->value) : std::string(), fmt::format("{}", c.limit),
                         csv_field(c.unit), g ? csv_field(g->train) : std::string(),
                         has_speed(g) ? fmt::format("{}", g->speed_kmh) : std::string(),
                         g ? csv_field(g->location) : std::string());
    }
  return out;
}

nlohmann::ordered_json format_line_json(const std::vector<LineBridge>& bridges) {
  using nlohmann::ordered_json;
  ordered_json list = ordered_json::array();
  for (const LineBridge& b : bridges) {
    ordered_json checks = ordered_json::array();
    for (const CheckResult& c : b.report.checks) {
      const CheckCase* g = governing_case(c);
      checks.push_back({{"id", c.id},
                        {"verdict", verdict_name(c.verdict)},
                        {"limit", c.limit},
                        {"unit", c.unit},
                        {"value", g ? ordered_json(*g->value) : ordered_json(nullptr)},
                        {"train", g ? ordered_json(g->train) : ordered_json(nullptr)},
                        {"speed_kmh", has_speed(g) ? ordered_json(g->speed_kmh) : ordered_json(nullptr)},
                        {"location", g ? ordered_json(g->location) : ordered_json(nullptr)}});
    }
    list.push_back({{"structure", b.name}, {"verdict", verdict_name(b.report.overall)}, {"checks", checks}});
  }
  return list;
}

}  // namespace railvsi::scheduler
