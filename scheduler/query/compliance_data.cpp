#include "query/compliance_data.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <map>
#include <memory>
#include <limits>
#include <set>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "analysis/static_influence.hpp"
#include "compliance/code_values.hpp"
#include "compliance/stored_checks.hpp"
#include "io/json_document.hpp"
#include "io/scene_loader.hpp"
#include "io/train_loader.hpp"
#include "compliance/check_limits.hpp"
#include "query/price_figures.hpp"
#include "query/static_effects.hpp"
#include "query/stored_statics.hpp"
#include "query/study_results.hpp"
#include "report/governing_figures.hpp"
#include "report/mode_shapes.hpp"
#include "simulation/deck_twist.hpp"
#include "simulation/static_equilibrium.hpp"
#include "planning/deck_frequencies.hpp"
#include "planning/rung_runner.hpp"

namespace railvsi::scheduler {
namespace {

using nlohmann::json;

std::string case_label(const JobResult& j) {
  return fmt::format("{} at {:g} km/h, {}{}", j.train, j.speed_kmh, j.irregularity,
                     j.variant == "nominal" ? std::string() : ", " + j.variant);
}

// Largest value per speed over the profiles of one train (the envelope a
// designer plots against speed), in the order of increasing speed.
std::vector<std::pair<double, double>> per_speed_maximum(const std::vector<const JobResult*>& jobs,
                                                         const std::string& quantity) {
  std::map<double, double> by_speed;
  for (const JobResult* j : jobs) {
    const auto v = j->overall(quantity);
    auto [it, fresh] = by_speed.try_emplace(j->speed_kmh, v ? *v : std::nan(""));
    if (!fresh && v && (std::isnan(it->second) || *v > it->second)) it->second = *v;
  }
  return {by_speed.begin(), by_speed.end()};
}

struct TrainInfo {
  std::string name;
  std::string source;                 // description and sources of a library file
};

// What the study's train list says about each train (by the label the jobs
// carry: a library name, or the name of an inline train).
std::map<std::string, TrainInfo> train_infos(const json& study) {
  std::map<std::string, TrainInfo> out;
  for (const json& t : study.value("trains", json::array())) {
    json file;
    std::string name;
    if (t.is_string() || (t.is_object() && t.contains("library"))) {
      name = t.is_string() ? t.get<std::string>() : t.at("library").get<std::string>();
      try {
        file = read_json_file(train_library_dir() / (name + ".json"));
      } catch (const std::exception&) {
        file = json::object();
      }
    } else if (t.is_object()) {
      file = t;
      name = t.value("name", std::string("inline train"));
    }
    TrainInfo info{name, ""};
    std::string source = file.value("description", std::string());
    for (const json& s : file.value("sources", json::array())) source += (source.empty() ? "" : " Source: ") + s.get<std::string>();
    info.source = source.empty() ? "given in the study document" : source;
    out[name] = info;
  }
  return out;
}

// The span of a bridge-2d structure that contains x (supports in info).
std::optional<double> span_at(const StructureInfo& info, double x_m) {
  const auto& s = info.support_x_m;
  for (std::size_t i = 0; i + 1 < s.size(); ++i)
    if (x_m >= s[i] && x_m <= s[i + 1]) return s[i + 1] - s[i];
  return std::nullopt;
}

std::vector<double> spans_of(const std::vector<double>& supports_x_m) {
  std::vector<double> spans;
  for (std::size_t i = 0; i + 1 < supports_x_m.size(); ++i) spans.push_back(supports_x_m[i + 1] - supports_x_m[i]);
  return spans;
}

// The check of a stored quantity against an upper limit, one case per job.
CheckResult quantity_check(CheckResult check, const std::vector<JobResult>& jobs) {
  // The bound of the structure is named only when the study has several.
  const bool variants =
      std::any_of(jobs.begin(), jobs.end(), [](const JobResult& j) { return j.variant != "nominal"; });
  std::vector<CheckCase> cases;
  for (const JobResult& j : jobs)
    cases.push_back({j.train, j.speed_kmh, j.irregularity, j.overall(check.quantity), j.id, "",
                     variants ? j.variant : "", j.error_estimate(check.quantity)});
  return evaluate_upper_limit(std::move(check), cases);
}

std::string fidelity_text(const JobResult& j) {
  if (j.fidelity.empty()) return "not run";
  const json f = json::parse(j.fidelity);
  std::string model = f.value("model", std::string("?"));
  if (f.value("contact_law", std::string("none")) != "none")
    model += ", " + f.value("contact_law", std::string()) + (f.value("unilateral", false) ? " (unilateral)" : "");
  return fmt::format("{}, {} on {} ({} structure DOFs), HHT alpha {:g}", model, f.value("solver_path", std::string()),
                     f.value("structure_backend", std::string()), f.value("structure_dofs", 0),
                     f.value("hht_alpha", 0.0));
}

// EN 1990 A2.4.4.2.2: the twist envelope of every job against the limit
// of Table A2.7 for the line speed (study's line_speed_kmh, else its
// highest speed: the stricter limit).
CheckResult deck_twist_check(const StructureModel& structure, const std::vector<int>& rail_lines, const json& study,
                             double max_speed_kmh, const std::vector<JobResult>& jobs) {
  CheckResult c;
  c.id = "deck_twist";
  c.title = "Deck twist over 3 m";
  c.unit = "mm";
  const bool line = study.contains("line_speed_kmh");
  const double speed_kmh = line ? study.at("line_speed_kmh").get<double>() : max_speed_kmh;
  const CodeValue code = twist_limit_mm_per_3m(speed_kmh);
  c.clause = code.clause;
  const DeckTwistGauge gauge = make_deck_twist_gauge(structure, rail_lines);
  if (!gauge.available()) {
    c.verdict = Verdict::kNotEvaluated;
    c.note = gauge.unavailable + ".";
    c.note[0] = static_cast<char>(std::toupper(static_cast<unsigned char>(c.note[0])));
    return c;
  }
  c.quantity = "deck_twist_mm_per_3m";
  c.limit = code.value;
  c.limit_verified = code.verified;
  c = quantity_check(c, jobs);
  c.note = fmt::format("Limit for V = {:g} km/h ({}; 4.5 / 3.0 / 1.5 mm for V <= 120 / <= 200 / > 200 km/h). Cross "
                       "level between rail lines {} and {} (their lateral distance, not scaled to the 1.435 m "
                       "gauge), bases of 3 m over the deck.",
                       speed_kmh, line ? "the study's line_speed_kmh" : "the study's highest speed", gauge.rail_a,
                       gauge.rail_b);
  if (c.missing > 0)
    c.note += " Jobs without a twist value: failed or not run.";
  return c;
}

// The unit a quantity is shown in, and the factor from SI.
std::pair<std::string, double> display_unit(const std::string& quantity) {
  if (quantity.ends_with("_Nm")) return {"kNm", 1e-3};
  if (quantity.ends_with("_N")) return {"kN", 1e-3};
  if (quantity.ends_with("_rad")) return {"mrad", 1e3};
  if (quantity.ends_with("_m")) return {"mm", 1e3};
  if (quantity.ends_with("_mps2")) return {"m/s2", 1.0};
  return {"", 1.0};
}

// phi'dyn against speed (EN 1991-2 6.4.6.5), one figure per load effect
// that has a static value, one line per train: at each speed the largest
// phi'dyn over the locations (and the profiles, through the dynamic values).
// The circle marks the largest of the figure, a value of the table.
std::vector<ReportFigure> phi_dyn_figures(const std::vector<DynamicIncrement>& increments,
                                          const std::vector<std::string>& train_order) {
  struct Effect {
    const char* quantity;
    const char* name;
  };
  std::vector<ReportFigure> out;
  for (const Effect e : {Effect{"deck_displacement_m", "deck deflection"}, Effect{"bending_moment_Nm", "bending moment"},
                         Effect{"shear_force_N", "shear force"}}) {
    LinePlot plot;
    plot.title = std::string("phi'dyn of the ") + e.name;
    plot.x_label = "speed [km/h]";
    plot.y_label = "phi'dyn [-]";
    std::optional<std::pair<double, double>> largest;
    for (const std::string& t : train_order) {
      std::map<double, double> by_speed;
      for (const DynamicIncrement& d : increments) {
        if (d.train != t || d.quantity != e.quantity) continue;
        for (const auto& [v, phi] : d.phi_dyn_by_speed()) {
          const auto [it, fresh] = by_speed.try_emplace(v, phi);
          if (!fresh) it->second = std::max(it->second, phi);
        }
      }
      if (by_speed.empty()) continue;
      for (const auto& point : by_speed)
        if (!largest || point.second > largest->second) largest = point;
      plot.series.push_back({t, {by_speed.begin(), by_speed.end()}});
    }
    if (plot.series.empty()) continue;
    plot.marked = largest;
    plot.marked_label = fmt::format("largest {:.3g}", largest->second);
    out.push_back({plot,
                   std::string("phi'dyn = dynamic / static - 1 of the ") + e.name +
                       " against speed, one line per train: at each speed the largest over the locations (and "
                       "profiles); the static value is the same train's axle loads standing on the structure. The "
                       "circle marks the largest, as in the table.",
                   std::nullopt, ""});
  }
  return out;
}

// Stored quantities no check judges, against speed: what a designer reads
// beside the checks (EN 1991-2 6.4.6: displacement, section forces, end
// rotation), one line per train.
void add_response_figures(ComplianceReport& report, const std::vector<std::string>& train_order,
                          std::map<std::string, std::vector<const JobResult*>>& by_train, std::size_t profile_count) {
  struct Quantity {
    const char* name;
    const char* title;
  };
  for (const Quantity q : {Quantity{"deck_displacement_m", "Peak deck displacement"},
                           Quantity{"bending_moment_Nm", "Peak bending moment"},
                           Quantity{"shear_force_N", "Peak shear force"},
                           Quantity{"support_rotation_rad", "Peak deck end rotation"}}) {
    if (std::any_of(report.checks.begin(), report.checks.end(), [&](const CheckResult& c) { return c.quantity == q.name; }))
      continue;  // drawn with its check
    const auto [unit, scale] = display_unit(q.name);
    LinePlot plot;
    plot.title = q.title;
    plot.x_label = "speed [km/h]";
    plot.y_label = std::string(q.title) + " [" + unit + "]";
    bool any = false;
    for (const std::string& t : train_order) {
      PlotSeries s{t, per_speed_maximum(by_train[t], q.name)};
      for (auto& [v, y] : s.points) {
        any = any || std::isfinite(y);
        y *= scale;
      }
      plot.series.push_back(std::move(s));
    }
    if (!any) continue;
    report.response_figures.push_back(
        {plot,
         std::string(q.title) + " over the output points (supports for the end rotation) against speed, one line per "
                                "train" +
             (profile_count > 1 ? ", the largest value over the profiles at each speed." : "."),
         std::nullopt, ""});
  }
}

// The title block from the study document: "project" and "author" when it
// has them; the structure in one line.
TitleBlock title_block(const json& study, const std::string& name) {
  TitleBlock t;
  t.project = study.contains("project") && study.at("project").is_string() ? study.at("project").get<std::string>() : name;
  t.author = study.contains("author") && study.at("author").is_string() ? study.at("author").get<std::string>() : "";
  if (!study.contains("structure") || !study.at("structure").is_object()) return t;
  const json& st = study.at("structure");
  if (st.contains("file") || st.contains("import")) {
    t.structure = "imported structure model";
    return t;
  }
  std::string spans;
  for (const json& x : st.value("spans_m", json::array()))
    if (x.is_number()) spans += (spans.empty() ? "" : " + ") + fmt::format("{:g}", x.get<double>());
  t.structure = st.value("generator", std::string("structure"));
  if (!spans.empty())
    t.structure += fmt::format(": spans {} m, {}", spans, st.value("continuous", false) ? "continuous" : "simply supported");
  if (st.contains("deck") && st.at("deck").is_object()) {
    const json& d = st.at("deck");
    if (d.contains("mass_kg_per_m") && d.at("mass_kg_per_m").is_number())
      t.structure += fmt::format(", deck {:g} kg/m", d.at("mass_kg_per_m").get<double>());
    if (d.contains("EI_Nm2") && d.at("EI_Nm2").is_number())
      t.structure += fmt::format(", EI {:.4g} N m2", d.at("EI_Nm2").get<double>());
  }
  if (st.contains("track") && !st.at("track").is_null()) t.structure += ", with track";
  return t;
}

// One line for each code value the report uses that was not read in the
// standard's own text (code_values.hpp), saying where it comes from.
std::vector<std::string> unverified_lines(const std::vector<CheckResult>& checks, bool determinant_length,
                                          bool phi2) {
  std::vector<std::string> out;
  for (const CheckResult& c : checks) {
    if (c.limit_verified || c.verdict == Verdict::kNotEvaluated) continue;
    if (c.id == "wheel_unloading")
      out.push_back("Wheel unloading 0.6: no EN 1990 limit exists; 0.6 is common practice (the quasi-static limit "
                    "of EN 14363, Chinese and Japanese codes). Give checks.max_unloading_ratio to set the project's.");
    else if (c.id == "passenger_comfort")
      out.push_back(fmt::format("Comfort levels {}: the b_v values of EN 1990 Table A2.9 as quoted in the literature on "
                                "the code, not read in its text.",
                                [] {
                                  std::string l;
                                  for (const ComfortLevel& level : comfort_levels())
                                    l += (l.empty() ? "" : ", ") + fmt::format("{} {:g} m/s2", level.name, level.b_v_mps2);
                                  return l;
                                }()));
    else
      out.push_back(fmt::format("{}: limit {:g} {} from {}, as quoted in the literature on the code, not read in its "
                                "text.",
                                c.title, c.limit, c.unit, c.clause));
  }
  if (determinant_length)
    out.push_back(std::string("Determinant length L_Phi: ") + kDeterminantLengthClause +
                  " (L_Phi = span for simply supported girders; k times the mean span of a continuous deck), as "
                  "quoted in the literature, not read in the table's text.");
  out.push_back(std::string("phi'' (") + kPhiDoublePrimeClause +
                ", in the dynamic load effect): the formula as quoted in the literature, not read in the annex's text.");
  if (phi2) out.push_back("Phi2 (carefully maintained track): its formula as quoted, not read in the text.");
  return out;
}

// Histories of one governing case: its stored scene run again as the
// workers ran it (run_planned: the recorded rung, dt, contact law and
// escalation), every figure beside the value the job stored.
GoverningCase governing_case(Database& db, const JobResult& job, const std::string& why, const std::string& quantity) {
  GoverningCase g;
  g.heading = why + ": " + case_label(job);
  Scene scene = load_job_scene(db, job.id);
  scene.analysis.history_stride = 1;
  const Result r = run_planned(scene);
  g.status = std::string(r.status.name());
  GoverningRun run;
  run.scene = &scene;
  run.result = &r;
  run.job = job.id;
  run.cutoff_hz = job.cutoff_hz;
  run.check_quantity = quantity;
  g.figures = governing_figures(run, [&](const std::string& q, const std::string& location) {
    return job.value(q, location);
  });
  return g;
}

}  // namespace

ComplianceReport build_compliance_report(Database& db, const std::string& study_id, const ComplianceOptions& options) {
  ComplianceReport report;
  const StudyInfo info = study_info(db, study_id);
  std::string document_text;
  {
    Statement s = db.prepare("SELECT document FROM studies WHERE id = ?");
    s.bind(1, study_id).step();
    document_text = s.text(0);
  }
  const json study = json::parse(document_text);
  const json checks = info.checks;
  report.study_name = info.name;
  report.study_id = info.id;
  report.study_file = info.file;
  report.version = options.version;
  report.date = options.date;
  report.study_document = study.dump(2);
  report.accuracy_tolerance = info.tolerance;
  report.title = title_block(study, info.name);

  // The caller's jobs as they are (a copy of a bridge's 1,010 jobs and their
  // envelope maps cost as much as judging them).
  std::vector<JobResult> read_jobs;
  if (!options.jobs) read_jobs = study_results(db, {study_id, {}, {}, {}, {}, {}});
  const std::vector<JobResult>& jobs = options.jobs ? *options.jobs : read_jobs;
  std::vector<std::string> train_order;
  std::map<std::string, std::vector<const JobResult*>> by_train;
  for (const JobResult& j : jobs) {
    if (!by_train.count(j.train)) train_order.push_back(j.train);
    by_train[j.train].push_back(&j);
  }
  const auto infos = options.checks_only ? std::map<std::string, TrainInfo>{} : train_infos(study);
  for (const std::string& t : train_order) {
    if (options.checks_only) break;
    const auto it = infos.find(t);
    report.trains.push_back({t, it == infos.end() ? std::string("given in the study document") : it->second.source});
  }
  if (jobs.empty()) return report;  // a filter that keeps no job: nothing is evaluated

  // The structure, and each train as the jobs built it: on the nominal
  // structure when the study has bounds of it and the nominal among them.
  std::map<std::string, Scene> scenes;
  std::vector<std::string> variants;
  for (const JobResult& j : jobs)
    if (std::find(variants.begin(), variants.end(), j.variant) == variants.end()) variants.push_back(j.variant);
  // (The scenes the trains' static envelopes are stored by: stored_statics.)
  const StaticSceneJobs scene_jobs = static_scene_jobs(jobs);
  // The checks alone read the first train's scene (the structure); another
  // train's only when its static envelopes are not stored.
  const auto scene_of = [&](const std::string& t) -> const Scene& {
    auto it = scenes.find(t);
    if (it == scenes.end()) it = scenes.emplace(t, load_job_scene(db, scene_jobs.train_job.at(t))).first;
    return it->second;
  };
  for (const std::string& t : train_order)
    if (!options.checks_only || t == scene_jobs.train_job.begin()->first) scene_of(t);
  const Scene& first = scenes.begin()->second;
  const StructureModel& structure = *first.structure;
  const StructureInfo& sinfo = structure.info();
  const DeckFrequencies freq = deck_frequencies(structure);
  const double cutoff = jobs.empty() ? 0.0 : jobs.front().cutoff_hz;
  // An import without supports_x_m: the supports read from its modes.
  const std::vector<double> spans = spans_of(freq.supports.x_m);
  // The structure as the jobs give it (a bridge of a line study has its own).
  const json scene_structure = [&] {
    Statement s = db.prepare("SELECT json_extract(scene, '$.structure') FROM job_scenes WHERE job_id = ?");
    return s.bind(1, jobs.front().id).step() && !s.is_null(0) ? json::parse(s.text(0)) : json::object();
  }();
  const bool continuous = scene_structure.value("continuous", false);
  const double L_phi = determinant_length_m(spans, continuous);
  const bool phi2 = checks.value("dynamic_factor", std::string("phi3")) == "phi2";
  const double Phi = L_phi > 0.0 ? (phi2 ? dynamic_factor_phi2(L_phi) : dynamic_factor_phi3(L_phi)) : 0.0;
  const double alpha = checks.value("lm71_alpha", 1.0);
  double max_speed_kmh = 0.0;
  double min_speed_kmh = std::numeric_limits<double>::infinity();
  for (const JobResult& j : jobs) max_speed_kmh = std::max(max_speed_kmh, j.speed_kmh);
  for (const JobResult& j : jobs) min_speed_kmh = std::min(min_speed_kmh, j.speed_kmh);

  if (!options.checks_only) {
    // Model summary.
    report.model.push_back({"structure", sinfo.source});
    if (variants.size() > 1 || (variants.size() == 1 && variants.front() != "nominal")) {
      std::string list;
      for (const std::string& v : variants) list += (list.empty() ? "" : "; ") + v;
      report.model.push_back({"bounds of the structure (EN 1991-2 6.4.6.3)",
                              list + ". The values below are those of the " +
                                  (std::find(variants.begin(), variants.end(), "nominal") != variants.end()
                                       ? std::string("nominal structure")
                                       : "first bound") +
                                  "; each job records its bound."});
    }
    if (!spans.empty()) {
      std::string s;
      for (double x : spans) s += (s.empty() ? "" : ", ") + fmt::format("{:g}", x);
      report.model.push_back({"spans [m]", s + (continuous ? " (continuous)" : " (simply supported)") +
                                               (freq.supports.from_modes ? ", supports read from the deck modes "
                                                                           "(the model gives none)"
                                                                         : "")});
    }
    if (scene_structure.contains("deck")) {
      const json& deck = scene_structure.at("deck");
      for (const char* key : {"EI_Nm2", "first_frequency_hz", "mass_kg_per_m"})
        if (deck.contains(key)) report.model.push_back({std::string("deck ") + key, deck.at(key).dump()});
    }
    report.model.push_back({"degrees of freedom",
                            fmt::format("{} (deck {}, track {})", structure.num_dofs(), sinfo.deck_dofs, sinfo.track_dofs)});
    report.model.push_back({"damping", sinfo.damping_ratio ? fmt::format("{:.3g} % ({})", *sinfo.damping_ratio * 100,
                                                                         sinfo.damping_source)
                                                           : sinfo.damping_source});
    report.model.push_back({"f0, first deck bending frequency", freq.f0_hz > 0 ? fmt::format("{:.4g} Hz", freq.f0_hz) : "not found"});
    report.model.push_back({"f3, third mode of the member", freq.f3_hz > 0 ? fmt::format("{:.4g} Hz", freq.f3_hz)
                                                                     : fmt::format("not found among the {} lowest modes",
                                                                                   freq.modes_searched)});
    report.model.push_back({"deck acceleration cut-off max(30 Hz, 1.5 f0, f3) (EN 1990 A2.4.4.2.1)",
                            fmt::format("{:.4g} Hz", cutoff)});
    if (L_phi > 0.0)
      report.model.push_back({"determinant length L_Phi (" + std::string(kDeterminantLengthClause) + ", unverified)",
                              fmt::format("{:.4g} m", L_phi)});
    if (Phi > 0.0)
      report.model.push_back({std::string(phi2 ? "Phi2" : "Phi3") + " (" + kPhiClause + ")" +
                                  ((phi2 ? kPhi2Verified : kPhi3Verified) ? "" : ", unverified"),
                              fmt::format("{:.4g}", Phi)});
    report.model.push_back({"LM71 classification factor alpha (EN 1991-2 6.3.2(3))", fmt::format("{:g}", alpha)});
    report.model.push_back({"output points", std::to_string(structure.outputs().size())});

    // Rungs and time steps.
    // Grouped by model and the step the answers ran at; the reason shown is
    // the first job's (the binding bound may differ between speeds of one
    // group), with its planned step when it escalated to a finer one.
    std::map<std::pair<std::string, double>, std::pair<std::string, int>> rungs;
    for (const JobResult& j : jobs) {
      auto& [reason, n] = rungs[{fidelity_text(j), j.ran_dt_s}];
      if (n++ == 0)
        reason = j.ran_dt_s == j.dt_s ? j.dt_reason
                                      : fmt::format("escalated from its planned {:g} s: {}", j.dt_s, j.dt_reason);
    }
    for (const auto& [key, value] : rungs)
      report.rungs.push_back({key.first, fmt::format("{:g} s (first job: {})", key.second, value.first), value.second});

    // Jobs without a clean result.
    {
      Statement s = db.prepare("SELECT warnings FROM jobs WHERE id = ?");
      for (const JobResult& j : jobs) {
        std::string detail = j.error;
        if (s.reset(), s.bind(1, j.id).step() && !s.is_null(0)) {
          const json w = json::parse(s.text(0), nullptr, false);
          if (w.is_array())
            for (const json& item : w) detail += (detail.empty() ? "" : "; ") + item.value("code", std::string()) + ": " +
                                                 item.value("message", std::string());
        }
        const bool clean = j.state == "done" && (j.status.empty() || j.status == "ok") && detail.empty();
        if (!clean) report.issues.push_back({case_label(j), j.state + (j.status.empty() ? "" : " (" + j.status + ")"), detail});
      }
    }

    add_price_figures(db, study_id, report);
  }

  // Checks on stored quantities: the table of rules (compliance/stored_checks).
  {
    // The bound of the structure is named only when the study has several.
    const bool variants =
        std::any_of(jobs.begin(), jobs.end(), [](const JobResult& j) { return j.variant != "nominal"; });
    std::vector<StoredCase> cases;
    cases.reserve(jobs.size());
    for (const JobResult& j : jobs) {
      StoredCase c;
      c.at = {j.train, j.speed_kmh, j.irregularity, std::nullopt, j.id, "", variants ? j.variant : ""};
      c.axle_forces = j.axle_forces.value_or(false);
      for (const StoredCheckRule& rule : stored_check_rules()) {
        c.values[rule.quantity] = j.overall(rule.quantity);
        c.error_estimates[rule.quantity] = j.error_estimate(rule.quantity);
      }
      cases.push_back(std::move(c));
    }
    for (CheckResult& c : evaluate_stored_checks(checks, cases)) report.checks.push_back(std::move(c));
  }

  // Static checks from the same structure: LM71 deflection and the dynamic
  // enhancement of each train against Phi x alpha x LM71.
  std::optional<StaticInfluence> influence;
  std::string static_note;
  try {
    influence.emplace(structure, first.analysis.contact.rail_lines);
  } catch (const std::exception& e) {
    static_note = std::string("Static influence lines could not be computed: ") + e.what();
  }
  std::vector<double> lm71_deflection_m(structure.outputs().size(), 0.0);
  // The trains' static envelopes below, for phi'dyn: when every job has one
  // structure (no bounds of it), theirs is this one.
  KnownStatics known;
  if (influence && variants.size() == 1) known.influence = &*influence;
  if (influence) {
    // Each output point against the limit of its own span: the check is on
    // the utilisation deflection / (L/600), and the note gives millimetres.
    CheckResult c;
    c.id = "lm71_deflection";
    c.title = "Deflection under alpha x Phi x LM71, as a fraction of L/600";
    c.quantity = "lm71_deflection_utilisation";
    c.unit = "";
    c.clause = deflection_span_ratio().clause;
    c.limit = 1.0;
    c.limit_verified = deflection_span_ratio().verified;
    std::vector<CheckCase> cases;
    double worst = -1.0;
    for (std::size_t k = 0; k < structure.outputs().size(); ++k) {
      const OutputPoint& p = structure.outputs()[k];
      lm71_deflection_m[k] = influence->lm71(static_cast<int>(k)).max_deflection_m;
      const auto L = span_at(sinfo, p.x_m);
      if (!L || Phi <= 0.0) continue;
      const double deflection_m = alpha * Phi * lm71_deflection_m[k];
      const double utilisation = deflection_m / (*L / deflection_span_ratio().value);
      cases.push_back({"LM71", std::nan(""), "", utilisation, "", p.name});
      if (utilisation > worst) {
        worst = utilisation;
        c.note = fmt::format("Governing point {} (span {:g} m): LM71 {:.4g} mm x Phi {:.4g} x alpha {:g} = {:.4g} mm "
                             "against L/600 = {:.4g} mm.",
                             p.name, *L, lm71_deflection_m[k] * 1e3, Phi, alpha, deflection_m * 1e3, *L / 0.6);
      }
    }
    if (cases.empty()) {
      c.verdict = Verdict::kNotEvaluated;
      c.note = "No output point lies in a span with known supports (imported structure).";
      report.checks.push_back(c);
    } else {
      const std::string note = c.note;
      CheckResult r = evaluate_upper_limit(c, cases);
      r.note = note;
      report.checks.push_back(r);
    }
  }
  if (influence && Phi > 0.0) {
    CheckResult c;
    c.id = "dynamic_enhancement";
    c.title = "Dynamic load effect against Phi x alpha x LM71 (deflection; bending moment of a beam deck)";
    c.quantity = "dynamic_to_lm71_ratio";
    c.unit = "";
    c.clause = "EN 1991-2 6.4.6.5(3)";
    c.limit = 1.0;
    c.limit_verified = true;
    std::vector<CheckCase> cases;
    std::string worst_note;
    double worst = -1.0;
    const double phi2nd_speed = max_speed_kmh / 3.6;
    const double phi2nd = phi_double_prime(L_phi, freq.f0_hz, phi2nd_speed);
    // The sagging moment of LM71 at each output point of a beam deck (0:
    // none), the larger of the two sides of the section.
    const SectionForms& forms = influence->section_forms();
    std::vector<double> lm71_moment_Nm(structure.outputs().size(), 0.0);
    for (std::size_t k = 0; forms.available() && k < forms.points.size(); ++k)
      for (int f : {forms.points[k].moment_left, forms.points[k].moment_right})
        if (f >= 0) lm71_moment_Nm[k] = std::max(lm71_moment_Nm[k], influence->lm71_form(f).max_deflection_m);
    bool moment_partial = false;
    // The largest stored value of a quantity at a point over a train's jobs;
    // all: every job stored one.
    struct Dynamic {
      double value = -1.0;
      const JobResult* job = nullptr;
      bool all = true;
    };
    const auto dynamic_max = [&](const std::string& train, const char* quantity, const std::string& point) {
      Dynamic d;
      for (const JobResult* j : by_train[train]) {
        const std::optional<double> v = j->value(quantity, point);
        if (!v) d.all = false;
        else if (*v > d.value) d.value = *v, d.job = j;
      }
      return d;
    };
    for (const std::string& t : train_order) {
      // Stored at submission (the same bits), else computed here.
      std::optional<TrainStatics> stored =
          read_train_statics(db, scene_jobs.structure_job, scene_jobs.train_job.at(t), *influence);
      const TrainStatics train_stat =
          stored ? std::move(*stored) : compute_train_statics(*influence, axle_loads(scene_of(t).train));
      // (Without forms it says why, with no values.)
      const StaticSectionEnvelope& section_stat = train_stat.sections;
      if (known.influence) known.trains[t] = train_stat;
      std::optional<double> ratio;
      const JobResult* gov_job = nullptr;
      std::string gov_point;
      bool missing = false;
      // One load effect at one point: (1 + phi'dyn + phi''/2) x static
      // against Phi alpha LM71; unit_scale and unit turn SI into the note's unit.
      const auto consider = [&](const std::string& point, const char* effect_name, double stat, const Dynamic& dyn,
                                double lm71, double unit_scale, const char* unit) {
        const double phi_dyn = dyn.value / stat - 1.0;
        const double effect = (1.0 + phi_dyn + 0.5 * phi2nd) * stat;
        const double r = effect / (Phi * alpha * lm71);
        if (!ratio || r > *ratio) ratio = r, gov_job = dyn.job, gov_point = point;
        if (r <= worst) return;
        worst = r;
        worst_note = fmt::format(
            "Governing: {} at {}, {}: static {:.4g} {}, dynamic {:.4g} {}, phi'dyn = {:.4g}, phi'' = {:.4g} ({}, "
            "unverified; v = {:g} km/h), (1 + phi'dyn + phi''/2) x static = {:.4g} {} against Phi alpha LM71 = "
            "{:.4g} {}. A ratio above 1 means the dynamic analysis governs the design load effect, not that the "
            "bridge fails.",
            t, point, effect_name, stat * unit_scale, unit, dyn.value * unit_scale, unit, phi_dyn, phi2nd,
            kPhiDoublePrimeClause, max_speed_kmh, effect * unit_scale, unit, Phi * alpha * lm71 * unit_scale, unit);
      };
      for (std::size_t k = 0; k < structure.outputs().size(); ++k) {
        const std::string& point = structure.outputs()[k].name;
        const double y_stat = train_stat.max_deflection_m.at(k);
        const Dynamic y = dynamic_max(t, "deck_displacement_m", point);
        missing = missing || !y.all;
        if (y.value >= 0.0 && y_stat > 0.0 && lm71_deflection_m[k] > 0.0)
          consider(point, "deflection", y_stat, y, lm71_deflection_m[k], 1e3, "mm");
        // The bending moment (beam decks): the same rule on M, when every
        // job of the train stored it (a study asking no section forces has none).
        if (k < section_stat.max_abs_bending_moment_Nm.size() && section_stat.max_abs_bending_moment_Nm[k] &&
            lm71_moment_Nm[k] > 0.0) {
          const double m_stat = *section_stat.max_abs_bending_moment_Nm[k];
          const Dynamic m = dynamic_max(t, "bending_moment_Nm", point);
          moment_partial = moment_partial || !m.all;
          if (m.all && m.value >= 0.0 && m_stat > 0.0)
            consider(point, "bending moment", m_stat, m, lm71_moment_Nm[k], 1e-3, "kNm");
        }
      }
      cases.push_back({t, gov_job ? gov_job->speed_kmh : 0.0, gov_job ? gov_job->irregularity : "",
                       missing ? std::nullopt : ratio, gov_job ? gov_job->id : "", gov_point});
    }
    CheckResult r = evaluate_upper_limit(c, cases);
    r.note = worst_note;
    if (moment_partial)
      r.note += " The bending moment is left out where a train's jobs did not all store it (asks without "
                "section_forces, or a structure without a beam deck).";
    report.checks.push_back(r);
  }
  if (!static_note.empty()) report.notes.push_back(static_note);
  // phi'dyn of each load effect per train and location (EN 1991-2
  // 6.4.6.5), as a table beside the check above.
  if (!options.checks_only) try {
    std::vector<std::string> unused;
    const std::vector<DynamicIncrement> increments =
        dynamic_increments(db, jobs, unused, known.influence ? &known : nullptr);
    for (const DynamicIncrement& d : increments) {
      const auto [unit, scale] = display_unit(d.quantity);
      PhiDynRow row{d.train, d.quantity, d.location, unit, d.static_value * scale, std::nullopt, d.governing_speed_kmh,
                    d.phi_dyn()};
      if (d.dynamic_value) row.dynamic_value = *d.dynamic_value * scale;
      report.phi_dyn.push_back(row);
    }
    report.phi_dyn_figures = phi_dyn_figures(increments, train_order);
  } catch (const std::exception& e) {
    report.notes.push_back(std::string("phi'dyn not computed: ") + e.what());
  }
  report.checks.push_back(deck_twist_check(structure, first.analysis.contact.rail_lines, study, max_speed_kmh, jobs));
  // Dynamic against Phi x LM71 says which governs the design load effect
  // (EN 1991-2 6.4.6.5(3)), not whether the bridge passes: not in the overall.
  {
    std::vector<CheckResult> verdicts;
    for (const CheckResult& c : report.checks)
      if (c.id != "dynamic_enhancement") verdicts.push_back(c);
    report.overall = overall_verdict(verdicts);
  }
  if (options.checks_only) return report;

  // Response against speed for each check on stored quantities.
  std::set<std::string> profiles;
  for (const JobResult& j : jobs) profiles.insert(j.irregularity);
  const std::size_t profile_count = profiles.size();
  for (const CheckResult& c : report.checks) {
    if (c.quantity.empty() || c.verdict == Verdict::kNotEvaluated || c.id == "lm71_deflection" ||
        c.id == "dynamic_enhancement")
      continue;
    LinePlot plot;
    plot.title = c.title;
    plot.x_label = "speed [km/h]";
    plot.y_label = c.title + (c.unit.empty() ? "" : " [" + c.unit + "]");
    plot.limit = c.limit;
    plot.limit_label = fmt::format("limit {:.4g}", c.limit);
    for (const std::string& t : train_order) plot.series.push_back({t, per_speed_maximum(by_train[t], c.quantity)});
    if (c.governing && c.governing->value) {
      plot.marked = std::pair{c.governing->speed_kmh, *c.governing->value};
      plot.marked_label = "governing";
    }
    // HSLM-A trains carry their coach length D (resonance at v = f0 D / i):
    // those of the governing train inside the speed range, labelled.
    std::string resonance_train;
    if (c.governing && freq.f0_hz > 0.0 && scenes.count(c.governing->train)) {
      const double D = scenes.at(c.governing->train).train.coach_length_m;
      for (int i = 1; D > 0.0 && i <= 4; ++i) {
        const double v = freq.f0_hz * D / i * 3.6;
        if (v < min_speed_kmh || v > max_speed_kmh) continue;
        plot.x_marks.push_back(v);
        plot.x_mark_labels.push_back(fmt::format("i={}", i));
        resonance_train = c.governing->train;
      }
    }
    plot.x_marks_label = "v = f0 D / i";
    report.check_figures.push_back(
        {plot,
         c.title + " against speed, one line per train" +
             (profile_count > 1 ? ", the largest value over the profiles at each speed" : "") +
             "; the dashed red line is the limit and the circle the governing case." +
             (plot.x_marks.empty() ? ""
                                   : fmt::format(" Dotted lines: resonance speeds v = f0 D / i of {} (D = {:g} m, "
                                                 "f0 = {:.4g} Hz) inside the speed range.",
                                                 resonance_train, scenes.at(resonance_train).train.coach_length_m,
                                                 freq.f0_hz)),
         std::nullopt, c.id});
  }
  add_response_figures(report, train_order, by_train, profile_count);
  report.unverified = unverified_lines(report.checks, L_phi > 0.0, phi2);
  if (structure.num_dofs() <= kMaxDofsForDeckFrequencies && cutoff > 0.0)
    report.mode_shapes = deck_mode_shapes(first.structure, cutoff, 6);
  for (std::size_t k = 0; k < freq.lowest_hz.size(); ++k) {
    const double f = freq.lowest_hz[k];
    report.modes.push_back({static_cast<int>(k) + 1, f, f == freq.f0_hz ? "f0" : f == freq.f3_hz ? "f3" : ""});
  }
  {
    std::set<std::string> used;
    for (const JobResult& j : jobs) {
      if (j.fidelity.empty()) continue;
      const json f = json::parse(j.fidelity, nullptr, false);
      if (!f.is_object()) continue;
      const auto number = [&](const char* key) { return f.contains(key) && f.at(key).is_number() ? f.at(key).get<double>() : 0.0; };
      const std::string rung = f.contains("rung") && f.at("rung").is_string() && !f.at("rung").get<std::string>().empty()
                                   ? f.at("rung").get<std::string>()
                                   : std::string("as given");
      if (number("modes") > 0)
        used.insert(fmt::format("{}: the {:g} modes up to {:.4g} Hz", rung, number("modes"), number("modal_cutoff_hz")));
      else
        used.insert(fmt::format("{}: the whole structure ({:g} DOFs), integrated directly", rung,
                                number("structure_dofs")));
    }
    for (const std::string& u : used) report.modes_note += (report.modes_note.empty() ? "" : "; ") + u;
  }

  // Governing cases, re-simulated.
  if (options.histories) {
    std::set<std::string> done;
    for (const CheckResult& c : report.checks) {
      if (!c.governing || !c.governing->value || c.id == "lm71_deflection" || c.id == "dynamic_enhancement") continue;
      const auto it = std::find_if(jobs.begin(), jobs.end(), [&](const JobResult& j) {
        return j.train == c.governing->train && j.speed_kmh == c.governing->speed_kmh &&
               j.irregularity == c.governing->irregularity &&
               (c.governing->variant.empty() || j.variant == c.governing->variant);
      });
      if (it == jobs.end() || done.count(it->id) ||
          static_cast<int>(done.size()) >= options.max_governing_cases)
        continue;
      done.insert(it->id);
      report.governing_cases.push_back(governing_case(db, *it, c.title, c.quantity));
    }
  }
  return report;
}

}  // namespace railvsi::scheduler
