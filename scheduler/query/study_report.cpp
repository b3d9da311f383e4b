#include "query/study_report.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <string_view>
#include <tuple>

#include <fmt/format.h>

#include "core/terminal_text.hpp"
#include "compliance/check_limits.hpp"

namespace railvsi::scheduler {
namespace {

using nlohmann::ordered_json;

// The table's columns: overall quantity, heading, shown unit, scale to it, check key.
struct Column {
  const char* quantity;
  const char* heading;
  const char* unit;
  double scale;
  bool vehicles;  // a wheel or car-body quantity: none for trains of axle forces
};

constexpr Column kColumns[] = {
    {"deck_acceleration_mps2", "deck a", "m/s2, code filter", 1.0, false},
    {"deck_displacement_m", "deck w", "mm", 1e3, false},
    {"unloading_ratio", "dQ/Q", "", 1.0, true},
    {"carbody_acceleration_mps2", "body a", "m/s2", 1.0, true},
};

std::string shown(std::optional<double> v, double scale) {
  return v ? fmt::format("{:.4g}", *v * scale) : std::string("-");
}

std::string speed_text(double speed_kmh) { return fmt::format("{:g}", speed_kmh); }

ordered_json number(std::optional<double> v) {
  return v && std::isfinite(*v) ? ordered_json(*v) : ordered_json(nullptr);
}

// A value of a run with warnings carries a mark (docs/user-guide.md "Run health").
constexpr const char* kWarningMark = "*";

std::string marked(const std::string& text, bool warned) { return warned ? text + kWarningMark : text; }

// An error estimate beyond the study's accuracy tolerance never passes silently.
constexpr const char* kEstimateMark = "!";

bool above_tolerance(std::optional<double> estimate, double tolerance) {
  return estimate && std::abs(*estimate) > tolerance;
}

// "±0.40 %" beside a governing value (the estimate's sign in json and csv).
std::string estimate_note(double estimate, double tolerance) {
  return fmt::format("\u00b1{:.2f} %{}", 100.0 * std::abs(estimate),
                     above_tolerance(estimate, tolerance) ? kEstimateMark : "");
}

const JobResult* governing_job(const std::vector<JobResult>& jobs, const TrainEnvelope& e) {
  for (const JobResult& j : jobs)
    if (j.train == e.train && j.speed_kmh == e.governing_speed_kmh && j.irregularity == e.governing_irregularity &&
        j.variant == e.governing_variant)
      return &j;
  return nullptr;
}

// Is it a line study (its "structures"): rows name their bridge?
bool is_line(const std::vector<JobResult>& jobs) {
  return std::any_of(jobs.begin(), jobs.end(), [](const JobResult& j) { return !j.structure.empty(); });
}

// Does the study run several bounds of the structure (its "variants")?
bool has_variants(const std::vector<JobResult>& jobs) {
  return std::any_of(jobs.begin(), jobs.end(), [](const JobResult& j) { return j.variant != "nominal"; });
}

// The profile cell of the job table: the profile, and the bound when there are several.
std::string case_label(const JobResult& j, bool variants) {
  return variants ? j.irregularity + ", " + j.variant : j.irregularity;
}

bool any_value(const std::vector<JobResult>& jobs, const char* quantity) {
  return std::any_of(jobs.begin(), jobs.end(), [&](const JobResult& j) { return j.overall(quantity).has_value(); });
}

}  // namespace

std::string csv_field(const std::string& text) {
  // A name that a spreadsheet would read as a formula (=, +, -, @, or a tab
  // or CR first) is written after a quote: the CSV is meant for spreadsheets,
  // and a train named =HYPERLINK(...) must stay text there.
  const std::string s = !text.empty() && std::string_view("=+-@\t\r").find(text.front()) != std::string_view::npos
                            ? "'" + text
                            : text;
  if (s.find_first_of(",\"\n\r") == std::string::npos) return s;
  std::string out = "\"";
  for (char c : s) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

std::vector<TrainEnvelope> study_envelope_over_speeds(const std::vector<JobResult>& jobs, const std::string& quantity) {
  std::vector<CaseValue> cases;
  std::map<std::string, std::size_t> train_order;
  for (const JobResult& j : jobs) {
    cases.push_back({j.train, j.speed_kmh, j.irregularity, j.overall(quantity), j.variant});
    train_order.try_emplace(j.train, train_order.size());
  }
  std::vector<TrainEnvelope> out = envelope_over_speeds(cases, extreme_of(quantity).value_or(Extreme::kMax));
  std::stable_sort(out.begin(), out.end(), [&](const TrainEnvelope& a, const TrainEnvelope& b) {
    return train_order[a.train] < train_order[b.train];
  });
  return out;
}

namespace {

// Tables fit an 80-column terminal: labels longer than their share are cut
// with "~" (csv and json carry them whole).
constexpr std::size_t kTableWidth = 80;

std::string fit(const std::string& text, std::size_t width) {
  const std::string safe = terminal_safe(text);
  if (safe.size() <= width) return safe;
  return width == 0 ? std::string() : safe.substr(0, width - 1) + "~";
}

// Widths of the two label columns so that `fixed` more columns fit.
std::pair<std::size_t, std::size_t> label_widths(std::size_t train_w, std::size_t irr_w, std::size_t fixed) {
  while (train_w + irr_w + fixed > kTableWidth && (train_w > 8 || irr_w > 10)) {
    if (irr_w > 10 && irr_w >= train_w) --irr_w;
    else if (train_w > 8) --train_w;
    else --irr_w;
  }
  return {train_w, irr_w};
}

// A line cut to the table width (the last column is free text).
std::string table_line(std::string line) {
  line.erase(line.find_last_not_of(' ') + 1);
  if (line.size() > kTableWidth) line = line.substr(0, kTableWidth - 1) + "~";
  return line + "\n";
}

std::vector<SeededValue> seeded_values(const std::vector<JobResult>& jobs, const std::string& quantity) {
  std::vector<SeededValue> rows;
  for (const JobResult& j : jobs)
    if (!j.profile_family.empty()) rows.push_back({j.train, j.speed_kmh, j.profile_family, j.overall(quantity)});
  return rows;
}

// Text (already terminal-safe) in lines of at most kTableWidth, each
// starting with indent.
std::string wrapped(const std::string& text, const std::string& indent) {
  std::string out, line = indent;
  std::size_t start = 0;
  while (start < text.size()) {
    std::size_t end = text.find(' ', start);
    if (end == std::string::npos) end = text.size();
    const std::string word = text.substr(start, end - start);
    if (line.size() > indent.size() && line.size() + 1 + word.size() > kTableWidth) {
      out += table_line(line);
      line = indent;
    }
    line += (line.size() > indent.size() ? " " : "") + word;
    start = end + 1;
  }
  return out + table_line(line);
}

// Which rungs ran, with their modes, dt and who chose them, and what each
// ignores and why (once per rung): the fidelity records of the jobs.
std::string fidelity_block(const std::vector<JobResult>& jobs) {
  std::map<std::string, std::int64_t> rungs;
  std::map<std::string, std::string> ignores;
  for (const JobResult& j : jobs) {
    if (j.fidelity.empty()) continue;
    const nlohmann::json f = nlohmann::json::parse(j.fidelity);
    const std::string rung = f.value("rung", std::string());
    if (rung.empty()) continue;
    const int modes = f.value("modes", 0);
    std::string line = rung;
    if (modes > 0) line += fmt::format(", {} modes to {:.1f} Hz", modes, f.value("modal_cutoff_hz", 0.0));
    // chosen_by is "planner", "pinned" (the study's fidelity) or "analysis" (its dt): said as a phrase.
    const std::string by = f.value("chosen_by", std::string());
    line += fmt::format(", dt {:.3g} s, {}", f.value("dt_s", 0.0),
                        by == "pinned" ? "pinned by the study" : by == "analysis" ? "as given in analysis" : "chosen by " + by);
    if (f.contains("escalation") && f.at("escalation").is_string()) line += ", escalated to unilateral Hertz";
    ++rungs[line];
    std::string& why = ignores[rung];
    if (why.empty() && f.contains("ignores"))
      for (const auto& i : f.at("ignores"))
        why += wrapped(fmt::format("ignores {}: {}", terminal_safe(i.value("what", std::string())),
                                   terminal_safe(i.value("why", std::string()))),
                       "    ");
  }
  if (rungs.empty()) return "";
  std::string out = "\nfidelity (rung, modes, dt, chosen by: jobs; the reasons: --format json):\n";
  for (const auto& [line, n] : rungs) out += table_line(fmt::format("{}: {} jobs", terminal_safe(line), n));
  for (const auto& [rung, why] : ignores)
    if (!why.empty()) out += table_line("  " + terminal_safe(rung)) + why;
  return out;
}

std::map<std::string, std::string> family_labels(const std::vector<JobResult>& jobs) {
  std::map<std::string, std::string> labels;
  for (const JobResult& j : jobs)
    if (!j.profile_family.empty()) labels.emplace(j.profile_family, j.family_label);
  return labels;
}

}  // namespace

std::vector<SampleStatistics> study_profile_statistics(const std::vector<JobResult>& jobs, const std::string& quantity) {
  return profile_statistics(seeded_values(jobs, quantity), extreme_of(quantity).value_or(Extreme::kMax));
}

bool at_edge_of_speed_range(const std::vector<JobResult>& jobs, const TrainEnvelope& e) {
  std::set<double> speeds;
  for (const JobResult& j : jobs)
    if (j.train == e.train) speeds.insert(j.speed_kmh);
  return e.value && speeds.size() >= 3 &&
         (e.governing_speed_kmh == *speeds.begin() || e.governing_speed_kmh == *speeds.rbegin());
}

std::string format_table(const StudyInfo& study, const std::vector<JobResult>& jobs) {
  std::vector<const Column*> columns;
  // The deck acceleration is always checked (its limit is the code's when
  // the study gives none): without a value its column says so ("-",
  // INCOMPLETE) instead of vanishing.
  for (const Column& c : kColumns)
    if (any_value(jobs, c.quantity) || std::string_view(c.quantity) == "deck_acceleration_mps2") columns.push_back(&c);
  const bool variants = has_variants(jobs);
  const char* irr_heading = variants ? "profile, bound" : "irregularity";
  std::size_t train_w = 5, irr_w = 12;
  std::vector<std::size_t> value_w;
  for (const Column* c : columns) value_w.push_back(std::string(c->heading).size());
  for (const JobResult& j : jobs) {
    train_w = std::max(train_w, terminal_safe(j.train).size());
    irr_w = std::max(irr_w, terminal_safe(case_label(j, variants)).size());
    for (std::size_t k = 0; k < columns.size(); ++k)
      value_w[k] = std::max(value_w[k], marked(shown(j.overall(columns[k]->quantity), columns[k]->scale),
                                                j.has_warnings() && j.overall(columns[k]->quantity).has_value())
                                             .size());
  }
  std::size_t fixed = 2 + 5 + 2 + 2 + 8 + 2 + 6;  // km/h, dt, a short state
  for (std::size_t w : value_w) fixed += 2 + w;
  std::tie(train_w, irr_w) = label_widths(train_w, irr_w, fixed);

  std::string out = table_line(
      fmt::format("study {} ({}): {} jobs shown", study.id.substr(0, 12), terminal_safe(study.name), jobs.size()));
  std::string units = "units: dt s";
  for (const Column* c : columns)
    if (*c->unit != '\0') units += fmt::format("; {} {}", c->heading, c->unit);
  out += table_line(units) + "\n";
  std::string heading = fmt::format("{:<{}}  {:>5}  {:<{}}  {:>8}", "train", train_w, "km/h", irr_heading, irr_w, "dt");
  for (std::size_t k = 0; k < columns.size(); ++k) heading += fmt::format("  {:>{}}", columns[k]->heading, value_w[k]);
  out += table_line(heading + "  state");
  for (const JobResult& j : jobs) {
    std::string line = fmt::format("{:<{}}  {:>5}  {:<{}}  {:>8.3g}", fit(j.train, train_w), train_w,
                                   speed_text(j.speed_kmh), fit(case_label(j, variants), irr_w), irr_w, j.ran_dt_s);
    for (std::size_t k = 0; k < columns.size(); ++k)
      line += fmt::format("  {:>{}}", marked(shown(j.overall(columns[k]->quantity), columns[k]->scale),
                                            j.has_warnings() && j.overall(columns[k]->quantity).has_value()),
                           value_w[k]);
    line += "  " + terminal_safe(j.state == "failed" && !j.status.empty() ? j.state + " (" + j.status + ")" : j.state);
    out += table_line(line);
  }

  // The envelope over speeds; notes that do not fit go on the next line.
  std::size_t etrain_w = 5, eirr_w = 12;
  for (const JobResult& j : jobs) {
    etrain_w = std::max(etrain_w, terminal_safe(j.train).size());
    eirr_w = std::max(eirr_w, terminal_safe(j.irregularity).size());
  }
  std::tie(etrain_w, eirr_w) = label_widths(etrain_w, eirr_w, 2 + 8 + 2 + 10 + 2 + 5 + 2 + 14);
  out += "\nenvelope over speeds (the governing value, and the case that gives it):\n";
  out += table_line(fmt::format("{:<{}}  {:<8}  {:>10}  {:>5}  {:<{}}  {}", "train", etrain_w, "quantity", "value",
                                "km/h", "irregularity", eirr_w, "check"));
  bool any_edge = false, any_estimate = false, any_above = false;
  // Trains given as axle forces have no wheel or car-body rows.
  const std::vector<JobResult> vehicle_jobs = jobs_with_vehicles(jobs);
  for (const Column* c : columns)
    for (const TrainEnvelope& e : study_envelope_over_speeds(c->vehicles ? vehicle_jobs : jobs, c->quantity)) {
      std::vector<std::string> notes;
      if (variants && e.value) notes.push_back("bound: " + e.governing_variant);
      if (const std::optional<double> limit = check_limit(study.checks, c->quantity)) {
        // The train's verdict by the rules of the report, against the same
        // limit (given, or the code's): never "ok" on missing cases.
        CheckResult check;
        check.limit = *limit;
        std::vector<CheckCase> cases;
        for (const JobResult& j : c->vehicles ? vehicle_jobs : jobs)
          if (j.train == e.train) cases.push_back({j.train, j.speed_kmh, j.irregularity, j.overall(c->quantity), j.id, ""});
        notes.push_back(fmt::format("{} (limit {})", verdict_name(evaluate_upper_limit(check, cases).verdict),
                                    shown(*limit, c->scale)));
      }
      if (at_edge_of_speed_range(jobs, e)) {
        notes.push_back("EDGE");
        any_edge = true;
      }
      if (e.cases_without_value > 0)
        notes.push_back(fmt::format("{} of {} cases without a value", e.cases_without_value, e.cases));
      const JobResult* g = e.value ? governing_job(jobs, e) : nullptr;
      if (const auto estimate = g ? g->error_estimate(c->quantity) : std::nullopt) {
        notes.insert(notes.begin(), estimate_note(*estimate, study.tolerance));
        any_estimate = true;
        any_above = any_above || above_tolerance(estimate, study.tolerance);
      }
      std::string line = fmt::format("{:<{}}  {:<8}  {:>10}  {:>5}  {:<{}}", fit(e.train, etrain_w), etrain_w,
                                     c->heading, marked(shown(e.value, c->scale), g && g->has_warnings()),
                                     e.value ? speed_text(e.governing_speed_kmh) : "-",
                                     fit(e.value ? e.governing_irregularity : "-", eirr_w), eirr_w);
      std::string note_text;
      for (const auto& n : notes) note_text += (note_text.empty() ? "" : "; ") + n;
      if (note_text.empty()) out += table_line(line);
      else if (line.size() + 2 + note_text.size() <= kTableWidth) out += table_line(line + "  " + note_text);
      else out += table_line(line) + table_line("    " + note_text);
    }
  if (any_edge)
    out += "EDGE: the governing value is at the first or last speed of the train's range;\n"
           "a larger value may lie beyond it (extend the speeds).\n";
  if (std::any_of(jobs.begin(), jobs.end(), [](const JobResult& j) { return j.has_warnings(); }))
    out += fmt::format("{} the run that gave this value has warnings (vsi query --format json lists them)\n",
                       kWarningMark);
  if (any_estimate)
    out += fmt::format("\u00b1: error estimate of the value, from its re-run at dt/2 (and one rung up when "
                       "accuracy.verify is given){}\n",
                       any_above ? fmt::format("; {} above the study's tolerance {:g} %", kEstimateMark,
                                               100.0 * study.tolerance)
                                 : "");

  // Several seeds of one random profile: mean, standard deviation and extreme.
  const auto labels = family_labels(jobs);
  const std::size_t stats_train_w = std::min<std::size_t>(etrain_w, 10);
  std::string block;
  for (const Column* c : columns) {
    const Extreme extreme = extreme_of(c->quantity).value_or(Extreme::kMax);
    for (const StatisticsOverSpeeds& s : statistics_over_speeds(study_profile_statistics(jobs, c->quantity), extreme))
      for (const auto& [governs, g] : {std::pair{"mean", s.governing_mean}, std::pair{"extreme", s.governing_extreme}}) {
        if (!g) continue;
        std::string line = fmt::format("{:<{}}  {:<6}  {:<10}  {:>2}  {:<7}  {:>5}  {:>8}  {:>8}  {:>8}",
                                       fit(s.train, stats_train_w), stats_train_w, c->heading, fit(labels.at(s.family), 10),
                                       g->samples, governs, speed_text(g->speed_kmh), shown(g->mean, c->scale),
                                       shown(g->std_dev, c->scale), shown(g->extreme, c->scale));
        if (g->without_value > 0) line += fmt::format("  {} without a value", g->without_value);
        block += table_line(line);
      }
  }
  if (!block.empty()) {
    out += "\nover random profiles (n seeds of one spectrum per train and speed: mean, standard\n"
           "deviation with divisor n - 1, extreme), at the speed where the mean governs and\n"
           "where the extreme governs; every speed: vsi query --format json:\n";
    out += table_line(fmt::format("{:<{}}  {:<6}  {:<10}  {:>2}  {:<7}  {:>5}  {:>8}  {:>8}  {:>8}", "train", stats_train_w,
                                  "qty", "profile", "n", "governs", "km/h", "mean", "std", "extreme"));
    out += block;
  }
  out += fidelity_block(jobs);
  return out;
}

std::string format_csv(const std::vector<JobResult>& jobs) {
  // A study with bounds of the structure gets a last column naming each row's;
  // a line study a first column naming its bridge.
  const bool variants = has_variants(jobs), line = is_line(jobs);
  std::string out = variants ? "train,irregularity,speed_kmh,quantity,location,value,state,variant,error_estimate\n"
                             : "train,irregularity,speed_kmh,quantity,location,value,state,error_estimate\n";
  if (line) out.insert(0, "structure,");
  for (const JobResult& j : jobs) {
    const std::string job = fmt::format("{}{},{},{}", line ? csv_field(j.structure) + "," : std::string(),
                                        csv_field(j.train), csv_field(j.irregularity), j.speed_kmh);
    std::string variant;
    if (variants) variant.append(",").append(csv_field(j.variant));
    if (j.envelopes.empty()) out += fmt::format("{},,,,{}{},\n", job, csv_field(j.state), variant);
    for (const auto& [quantity, locations] : j.envelopes)
      for (const auto& [location, value] : locations) {
        const auto estimate = j.error_estimate(quantity, location);
        // {} writes the shortest text that reads back to the same double.
        out += fmt::format("{},{},{},{},{}{},{}\n", job, quantity, csv_field(location),
                           value ? fmt::format("{}", *value) : std::string(), csv_field(j.state), variant,
                           estimate ? fmt::format("{}", *estimate) : std::string());
      }
  }
  return out;
}

std::string format_wide_csv(const std::vector<JobResult>& jobs) {
  // The columns: every quantity x location any job has, in map order (the
  // whole job's value, location "", first).
  std::map<std::string, std::set<std::string>> columns;
  for (const JobResult& j : jobs)
    for (const auto& [quantity, locations] : j.envelopes)
      for (const auto& [location, value] : locations) columns[quantity].insert(location);
  const bool variants = has_variants(jobs), line = is_line(jobs);
  std::string out = variants ? "train,irregularity,speed_kmh,variant,state" : "train,irregularity,speed_kmh,state";
  if (line) out.insert(0, "structure,");
  for (const auto& [quantity, locations] : columns)
    for (const std::string& location : locations)
      out.append(",").append(csv_field(location.empty() ? quantity : quantity + "@" + location));
  out += "\n";
  for (const JobResult& j : jobs) {
    if (line) out += csv_field(j.structure) + ",";
    out += fmt::format("{},{},{},{}{}", csv_field(j.train), csv_field(j.irregularity), j.speed_kmh,
                       variants ? csv_field(j.variant) + "," : std::string(), csv_field(j.state));
    for (const auto& [quantity, locations] : columns) {
      const auto q = j.envelopes.find(quantity);
      for (const std::string& location : locations) {
        std::optional<double> value;
        if (q != j.envelopes.end())
          if (const auto l = q->second.find(location); l != q->second.end()) value = l->second;
        out += value ? fmt::format(",{}", *value) : std::string(",");
      }
    }
    out += "\n";
  }
  return out;
}

namespace {

ordered_json case_json(const CheckCase& c) {
  const auto text = [](const std::string& s) { return s.empty() ? ordered_json(nullptr) : ordered_json(s); };
  return {{"train", c.train},
          {"speed_kmh", number(c.speed_kmh)},
          {"irregularity", text(c.irregularity)},
          {"location", text(c.location)},
          {"job_id", text(c.job_id)},
          {"error_estimate", number(c.error_estimate)}};
}

// Verdict, governing case and missing cases of a check (or of one train's
// part of it). For a check of a stored envelope quantity, whose cases are
// the jobs, the missing cases are also counted by the job's state ("done"
// for a job that ran but could not produce the value).
ordered_json verdict_json(const CheckResult& c, const std::map<std::string, std::string>& job_states) {
  const bool has_value = c.governing && c.governing->value;
  ordered_json out = {{"verdict", verdict_name(c.verdict)},
                      {"value", has_value ? number(c.governing->value) : ordered_json(nullptr)},
                      {"governing", has_value ? case_json(*c.governing) : ordered_json(nullptr)},
                      {"error_estimate", has_value ? number(c.governing->error_estimate) : ordered_json(nullptr)},
                      {"cases", c.cases},
                      {"missing", c.missing}};
  if (extreme_of(c.quantity)) {
    std::map<std::string, int> by_state;
    for (const CheckCase& k : c.all_cases)
      if (!k.value || !std::isfinite(*k.value)) {
        const auto state = job_states.find(k.job_id);
        ++by_state[state == job_states.end() ? std::string("unknown") : state->second];
      }
    out["missing_by_state"] = by_state;
  }
  return out;
}

}  // namespace

ordered_json format_checks_json(const std::vector<CheckResult>& checks, const std::vector<JobResult>& jobs) {
  std::map<std::string, std::string> job_states;
  for (const JobResult& j : jobs) job_states.emplace(j.id, j.state);
  ordered_json out = ordered_json::array();
  for (const CheckResult& c : checks) {
    const bool no_limit = c.verdict == Verdict::kNotEvaluated && c.limit == 0.0;
    ordered_json check = {{"id", c.id},
                          {"title", c.title},
                          {"quantity", c.quantity.empty() ? ordered_json(nullptr) : ordered_json(c.quantity)},
                          {"unit", c.unit},
                          {"limit", no_limit ? ordered_json(nullptr) : ordered_json(c.limit)},
                          {"clause", c.clause},
                          {"limit_verified", c.limit_verified}};
    check.update(verdict_json(c, job_states));
    check["note"] = c.note;
    ordered_json trains = ordered_json::array();
    for (const CheckResult& t : per_train(c)) {
      ordered_json one = {{"train", t.all_cases.front().train}};
      one.update(verdict_json(t, job_states));
      trains.push_back(std::move(one));
    }
    check["trains"] = std::move(trains);
    out.push_back(std::move(check));
  }
  return out;
}

std::string format_verdict_lines(const std::vector<CheckResult>& checks, Verdict overall) {
  std::string out = fmt::format("\nchecks: {}\n", verdict_name(overall));
  for (const CheckResult& c : checks) {
    std::string line = fmt::format("  {:<20}  {:<13}", fit(c.id, 20), verdict_name(c.verdict));
    std::vector<std::string> notes;
    if (c.governing && c.governing->value) {
      const CheckCase& g = *c.governing;
      line += fmt::format("  {:.4g}{}{} (limit {:.4g})", *g.value, c.unit.empty() ? "" : " ", c.unit, c.limit);
      std::string where = terminal_safe(g.train);
      if (std::isfinite(g.speed_kmh)) where += fmt::format(" {:g} km/h", g.speed_kmh);
      if (!g.location.empty()) where.append(" ").append(terminal_safe(g.location));
      notes.push_back(where);
    }
    if (c.missing > 0) notes.push_back(fmt::format("{} of {} cases without a value", c.missing, c.cases));
    line.erase(line.find_last_not_of(' ') + 1);
    std::string note_text;
    for (const auto& n : notes) note_text += (note_text.empty() ? "" : "; ") + n;
    if (note_text.empty()) out += table_line(line);
    else if (line.size() + 2 + note_text.size() <= kTableWidth) out += table_line(line + ", " + note_text);
    else out += table_line(line) + table_line("    " + note_text);
  }
  return out;
}

ordered_json format_json(const StudyInfo& study, const std::vector<JobResult>& jobs) {
  ordered_json out;
  out["study"] = {{"id", study.id},         {"name", study.name},
                  {"file", study.file},     {"checks", study.checks},
                  {"accuracy_tolerance", study.tolerance}};
  ordered_json list = ordered_json::array();
  for (const JobResult& j : jobs) {
    ordered_json envelopes = ordered_json::object();
    for (const auto& [quantity, locations] : j.envelopes)
      for (const auto& [location, value] : locations) envelopes[quantity][location.empty() ? "all" : location] = number(value);
    ordered_json job = {{"id", j.id},
                        {"train", j.train},
                        {"speed_kmh", j.speed_kmh},
                        {"irregularity", j.irregularity},
                        {"variant", j.variant},
                        {"structure", j.structure.empty() ? ordered_json(nullptr) : ordered_json(j.structure)},
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
    // Beside envelopes, the same shape: only the values that were verified.
    ordered_json estimates = ordered_json::object();
    for (const auto& [quantity, locations] : j.error_estimates)
      for (const auto& [location, e] : locations) estimates[quantity][location.empty() ? "all" : location] = e;
    job["error_estimates"] = std::move(estimates);
    list.push_back(std::move(job));
  }
  out["jobs"] = std::move(list);
  ordered_json over = ordered_json::array();
  for (const EnvelopeQuantity& q : envelope_quantities())
    for (const TrainEnvelope& e : study_envelope_over_speeds(jobs, std::string(q.name)))
      if (e.value) {
        const JobResult* g = governing_job(jobs, e);
        const auto estimate = g ? g->error_estimate(std::string(q.name)) : std::nullopt;
        over.push_back({{"train", e.train},
                        {"quantity", std::string(q.name)},
                        {"value", number(e.value)},
                        {"governing_speed_kmh", e.governing_speed_kmh},
                        {"governing_irregularity", e.governing_irregularity},
                        {"governing_variant", e.governing_variant},
                        {"cases", e.cases},
                        {"cases_without_value", e.cases_without_value},
                        {"at_edge_of_speed_range", at_edge_of_speed_range(jobs, e)},
                        {"error_estimate", number(estimate)},
                        {"error_estimate_above_tolerance", above_tolerance(estimate, study.tolerance)}});
      }
  out["envelope_over_speeds"] = std::move(over);
  // Over the seeds of each random profile, per train x speed (only when a
  // profile has several seeds).
  const auto labels = family_labels(jobs);
  ordered_json stats = ordered_json::array();
  for (const EnvelopeQuantity& q : envelope_quantities()) {
    // A quantity no job stores (the twist of a plane model) has no statistics.
    if (std::none_of(jobs.begin(), jobs.end(), [&](const JobResult& j) { return j.envelopes.count(std::string(q.name)); }))
      continue;
    for (const SampleStatistics& g : study_profile_statistics(jobs, std::string(q.name)))
      stats.push_back({{"train", g.train},
                       {"speed_kmh", g.speed_kmh},
                       {"profile", labels.at(g.family)},
                       {"quantity", std::string(q.name)},
                       {"samples", g.samples},
                       {"samples_without_value", g.without_value},
                       {"mean", number(g.mean)},
                       {"std_dev", number(g.std_dev)},
                       {q.extreme == Extreme::kMax ? "max" : "min", number(g.extreme)}});
  }
  out["profile_statistics"] = std::move(stats);
  return out;
}

}  // namespace railvsi::scheduler
