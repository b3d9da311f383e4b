#include "query/study_report.hpp"

#include <algorithm>
#include <cmath>
#include <map>

#include <fmt/format.h>

namespace railvsi::scheduler {
namespace {

using nlohmann::ordered_json;

// The table's columns: overall quantity, heading, scale to the shown unit, check key.
struct Column {
  const char* quantity;
  const char* heading;
  double scale;
  const char* check;
};

constexpr Column kColumns[] = {
    {"deck_acceleration_mps2", "deck a [m/s2]", 1.0, "deck_acceleration_limit_mps2"},
    {"deck_displacement_m", "deck w [mm]", 1e3, "deck_displacement_limit_m"},
    {"unloading_ratio", "dQ/Q", 1.0, "max_unloading_ratio"},
    {"carbody_acceleration_mps2", "body a [m/s2]", 1.0, "carbody_acceleration_limit_mps2"},
};

std::string shown(std::optional<double> v, double scale) {
  return v ? fmt::format("{:.4g}", *v * scale) : std::string("-");
}

std::string speed_text(double speed_kmh) { return fmt::format("{:g}", speed_kmh); }

ordered_json number(std::optional<double> v) {
  return v && std::isfinite(*v) ? ordered_json(*v) : ordered_json(nullptr);
}

std::string csv_field(const std::string& s) {
  if (s.find_first_of(",\"\n\r") == std::string::npos) return s;
  std::string out = "\"";
  for (char c : s) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

// A value of a run with warnings carries a mark (README "Run health").
constexpr const char* kWarningMark = "*";

std::string marked(const std::string& text, bool warned) { return warned ? text + kWarningMark : text; }

const JobResult* governing_job(const std::vector<JobResult>& jobs, const TrainEnvelope& e) {
  for (const JobResult& j : jobs)
    if (j.train == e.train && j.speed_kmh == e.governing_speed_kmh && j.irregularity == e.governing_irregularity)
      return &j;
  return nullptr;
}

bool any_value(const std::vector<JobResult>& jobs, const char* quantity) {
  return std::any_of(jobs.begin(), jobs.end(), [&](const JobResult& j) { return j.overall(quantity).has_value(); });
}

}  // namespace

std::vector<TrainEnvelope> study_envelope_over_speeds(const std::vector<JobResult>& jobs, const std::string& quantity) {
  std::vector<CaseValue> cases;
  std::map<std::string, std::size_t> train_order;
  for (const JobResult& j : jobs) {
    cases.push_back({j.train, j.speed_kmh, j.irregularity, j.overall(quantity)});
    train_order.try_emplace(j.train, train_order.size());
  }
  std::vector<TrainEnvelope> out = envelope_over_speeds(cases, extreme_of(quantity).value_or(Extreme::kMax));
  std::stable_sort(out.begin(), out.end(), [&](const TrainEnvelope& a, const TrainEnvelope& b) {
    return train_order[a.train] < train_order[b.train];
  });
  return out;
}

std::string format_table(const StudyInfo& study, const std::vector<JobResult>& jobs) {
  std::vector<const Column*> columns;
  for (const Column& c : kColumns)
    if (any_value(jobs, c.quantity)) columns.push_back(&c);
  std::size_t train_w = 5, irr_w = 12;
  for (const JobResult& j : jobs) {
    train_w = std::max(train_w, j.train.size());
    irr_w = std::max(irr_w, j.irregularity.size());
  }
  std::string out = fmt::format("study {} ({}): {} jobs shown\n\n", study.id.substr(0, 12), study.name, jobs.size());
  out += fmt::format("{:<{}}  {:>7}  {:<{}}  {:>9}", "train", train_w, "km/h", "irregularity", irr_w, "dt [s]");
  for (const Column* c : columns) out += fmt::format("  {:>13}", c->heading);
  out += "  state\n";
  for (const JobResult& j : jobs) {
    out += fmt::format("{:<{}}  {:>7}  {:<{}}  {:>9.3g}", j.train, train_w, speed_text(j.speed_kmh), j.irregularity,
                       irr_w, j.dt_s);
    for (const Column* c : columns)
      out += fmt::format("  {:>13}", marked(shown(j.overall(c->quantity), c->scale),
                                            j.has_warnings() && j.overall(c->quantity).has_value()));
    out += "  " + (j.state == "failed" && !j.status.empty() ? j.state + " (" + j.status + ")" : j.state) + "\n";
  }

  out += "\nenvelope over speeds (the governing value, and the case that gives it):\n";
  out += fmt::format("{:<{}}  {:<15}  {:>10}  {:>7}  {:<{}}  {}\n", "train", train_w, "quantity", "value", "km/h",
                     "irregularity", irr_w, "check");
  for (const Column* c : columns)
    for (const TrainEnvelope& e : study_envelope_over_speeds(jobs, c->quantity)) {
      std::string note;
      if (study.checks.contains(c->check) && e.value) {
        const double limit = study.checks.at(c->check).get<double>();
        note = fmt::format("{} (limit {})", *e.value <= limit ? "ok" : "EXCEEDED", shown(limit, c->scale));
      }
      if (e.cases_without_value > 0)
        note += fmt::format("{}{} of {} cases without a value", note.empty() ? "" : "; ", e.cases_without_value, e.cases);
      const JobResult* g = e.value ? governing_job(jobs, e) : nullptr;
      out += fmt::format("{:<{}}  {:<15}  {:>10}  {:>7}  {:<{}}  {}\n", e.train, train_w, c->heading,
                         marked(shown(e.value, c->scale), g && g->has_warnings()), e.value ? speed_text(e.governing_speed_kmh) : "-",
                         e.value ? e.governing_irregularity : "-", irr_w, note);
    }
  if (std::any_of(jobs.begin(), jobs.end(), [](const JobResult& j) { return j.has_warnings(); }))
    out += fmt::format("\n{} the run that gave this value has warnings (vsi query --format json lists them per job)\n",
                       kWarningMark);
  return out;
}

std::string format_csv(const std::vector<JobResult>& jobs) {
  std::string out = "train,irregularity,speed_kmh,quantity,location,value\n";
  for (const JobResult& j : jobs)
    for (const auto& [quantity, locations] : j.envelopes)
      for (const auto& [location, value] : locations)
        // {} writes the shortest text that reads back to the same double.
        out += fmt::format("{},{},{},{},{},{}\n", csv_field(j.train), csv_field(j.irregularity), j.speed_kmh, quantity,
                           csv_field(location), value ? fmt::format("{}", *value) : std::string());
  return out;
}

ordered_json format_json(const StudyInfo& study, const std::vector<JobResult>& jobs) {
  ordered_json out;
  out["study"] = {{"id", study.id}, {"name", study.name}, {"file", study.file}, {"checks", study.checks}};
  ordered_json list = ordered_json::array();
  for (const JobResult& j : jobs) {
    ordered_json envelopes = ordered_json::object();
    for (const auto& [quantity, locations] : j.envelopes)
      for (const auto& [location, value] : locations) envelopes[quantity][location.empty() ? "all" : location] = number(value);
    ordered_json job = {{"id", j.id},
                        {"train", j.train},
                        {"speed_kmh", j.speed_kmh},
                        {"irregularity", j.irregularity},
                        {"state", j.state},
                        {"status", j.status.empty() ? ordered_json(nullptr) : ordered_json(j.status)},
                        {"dt_s", j.dt_s},
                        {"dt_reason", j.dt_reason},
                        {"cutoff_hz", j.cutoff_hz},
                        {"wall_s", number(j.wall_s)},
                        {"loop_s", number(j.loop_s)},
                        {"fidelity", j.fidelity.empty() ? ordered_json(nullptr) : ordered_json::parse(j.fidelity)},
                        {"warnings", j.warnings.empty() ? ordered_json::array() : ordered_json::parse(j.warnings)},
                        {"envelopes", envelopes}};
    if (!j.error.empty()) job["error"] = j.error;
    list.push_back(std::move(job));
  }
  out["jobs"] = std::move(list);
  ordered_json over = ordered_json::array();
  for (const EnvelopeQuantity& q : envelope_quantities())
    for (const TrainEnvelope& e : study_envelope_over_speeds(jobs, std::string(q.name)))
      if (e.value)
        over.push_back({{"train", e.train},
                        {"quantity", std::string(q.name)},
                        {"value", number(e.value)},
                        {"governing_speed_kmh", e.governing_speed_kmh},
                        {"governing_irregularity", e.governing_irregularity},
                        {"cases", e.cases},
                        {"cases_without_value", e.cases_without_value}});
  out["envelope_over_speeds"] = std::move(over);
  return out;
}

}  // namespace railvsi::scheduler
