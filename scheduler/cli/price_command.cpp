#include "cli/price_command.hpp"

#include <cmath>
#include <iostream>
#include <sstream>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <nlohmann/json.hpp>

#include "cli/commands.hpp"
#include "cli/service_store.hpp"
#include "core/terminal_text.hpp"
#include "io/scene_loader.hpp"
#include "planning/cost_model.hpp"
#include "planning/accuracy_price.hpp"
#include "query/price_rows.hpp"
#include "query/price_sample.hpp"
#include "planning/deck_frequencies.hpp"
#include "workers/worker_pool.hpp"

namespace railvsi::cli {
namespace {

using nlohmann::ordered_json;

ordered_json number(std::optional<double> v) {
  if (!v || !std::isfinite(*v)) return nullptr;
  return *v;
}

ordered_json quantity_map(const std::map<std::string, std::optional<double>>& m) {
  ordered_json out = ordered_json::object();
  for (std::string_view q : price_quantities()) {
    const auto it = m.find(std::string(q));
    out[std::string(q)] = it == m.end() ? ordered_json(nullptr) : number(it->second);
  }
  return out;
}

ordered_json rung_json(const PriceRow& r) {
  ordered_json j;
  j["model"] = r.model;
  j["structure"] = r.structure;
  j["contact_law"] = r.contact_law;
  j["modes"] = r.modes ? ordered_json(*r.modes) : ordered_json(nullptr);
  j["dt_s"] = r.dt_s;
  return j;
}

std::string criterion() {
  return fmt::format(
      "Richardson on the reference rung's runs at h, 2h, 4h: d1 = v(2h) - v(h), d2 = v(4h) - v(2h); asymptotic when "
      "d1 and d2 have one sign and d2/d1 is in [{:g}, {:g}] (observed order 1 to 3); then error = (d1/(d2/d1 - 1)) / "
      "v*, the reference's own relative error",
      kRichardsonMinRatio, kRichardsonMaxRatio);
}

ordered_json price_json(const PriceReport& p) {
  ordered_json out;
  ordered_json ref = nullptr;
  if (p.reference.row) {
    const PriceRow& r = p.rows[*p.reference.row];
    ref = rung_json(r);
    ref["row"] = *p.reference.row;
    ref["values"] = quantity_map(r.values);
    ordered_json rich = ordered_json::object();
    for (const auto& [q, e] : p.reference.richardson) {
      rich[q] = {{"asymptotic", e.asymptotic},
                 {"order", number(e.order)},
                 {"error", number(e.error)},
                 {"last_change", number(e.last_change)}};
    }
    ref["richardson"] = rich;
    ordered_json dts = ordered_json::array();
    for (std::size_t i : p.reference.richardson_rows) dts.push_back(p.rows[i].dt_s);
    ref["richardson_dt_s"] = dts;
    ref["criterion"] = criterion();
  }
  out["reference"] = ref;
  ordered_json rows = ordered_json::array();
  for (std::size_t i = 0; i < p.rows.size(); ++i) {
    const PriceRow& r = p.rows[i];
    ordered_json j = rung_json(r);
    j["status"] = r.status;
    if (!r.ok()) j["message"] = r.message;
    j["steps"] = r.steps;
    j["cpu_s"] = r.cpu_s;
    j["wall_s"] = r.wall_s;
    j["setup_cpu_s"] = r.setup_cpu_s;
    j["cpu_predicted_s"] = number(r.cpu_predicted_s);
    j["warnings"] = r.warnings;
    j["values"] = quantity_map(r.values);
    j["errors"] = quantity_map(r.errors);
    ordered_json front = ordered_json::array();
    for (const auto& [q, rows_on] : p.pareto)
      if (std::find(rows_on.begin(), rows_on.end(), i) != rows_on.end()) front.push_back(q);
    j["pareto"] = front;
    rows.push_back(j);
  }
  out["rows"] = rows;
  ordered_json cheapest = ordered_json::object();
  for (std::string_view qv : price_quantities()) {
    const std::string q(qv);
    const auto pick = [&](const std::map<std::string, std::optional<std::size_t>>& m) -> ordered_json {
      const auto it = m.find(q);
      if (it == m.end() || !it->second) return nullptr;
      const PriceRow& r = p.rows[*it->second];
      ordered_json j = rung_json(r);
      j["row"] = *it->second;
      j["cpu_s"] = r.cpu_s;
      j["error"] = number(r.errors.at(q));
      return j;
    };
    cheapest[q] = {{"1%", pick(p.cheapest_1pct)}, {"5%", pick(p.cheapest_5pct)}};
  }
  out["cheapest"] = cheapest;
  ordered_json pareto = ordered_json::object();
  for (const auto& [q, idx] : p.pareto) pareto[q] = idx;
  out["pareto"] = pareto;
  out["policy"] = {{"dt_s", p.policy_dt_s}, {"reason", p.policy_reason}};
  out["cutoff_hz"] = p.cutoff_hz;
  out["threads"] = p.threads;
  out["wall_s"] = p.wall_s;
  out["cost_model"] = describe_cost_model();
  return out;
}

// Short column heads of the table, in price_quantities() order.
const char* const kShort[] = {"disp", "acc", "acc_raw", "Q_min", "dQ/Q", "loss", "body"};

std::string percent(std::optional<double> e) {
  if (!e) return "-";
  // Two decimals, or two digits for what two decimals would show as 0.00.
  const double pct = 100.0 * *e;
  return std::abs(pct) >= 0.005 || pct == 0.0 ? fmt::format("{:+.2f}%", pct) : fmt::format("{:+.1e}%", pct);
}

std::string modes_text(const PriceRow& r) { return r.modes ? std::to_string(*r.modes) : "all"; }

std::string price_table(const PriceReport& p) {
  std::ostringstream o;
  o << fmt::format("time-step policy: {:.3g} s ({})\n", p.policy_dt_s, p.policy_reason);
  o << fmt::format("{:<36} {:>5} {:>8} {:>8} {:>8} {:>8}", "rung (model / structure / contact)", "modes", "dt_ms",
                   "cpu_s", "pred_s", "wall_s");
  for (const char* s : kShort) o << fmt::format(" {:>9}", s);
  o << '\n';
  for (std::size_t i = 0; i < p.rows.size(); ++i) {
    const PriceRow& r = p.rows[i];
    o << fmt::format("{:<36} {:>5} {:>8.4g} ", r.model + " / " + r.structure + " / " + r.contact_law, modes_text(r),
                     1e3 * r.dt_s);
    if (r.status == "refused") {
      o << "refused: " << scheduler::terminal_safe(r.message) << '\n';
      continue;
    }
    o << fmt::format("{:>8.3g} {:>8.3g} {:>8.3g}", r.cpu_s, r.cpu_predicted_s.value_or(NAN), r.wall_s);
    if (!r.ok()) {
      o << "  " << r.status << ": " << scheduler::terminal_safe(r.message) << '\n';
      continue;
    }
    for (std::string_view qv : price_quantities()) {
      const std::string q(qv);
      const auto& front = p.pareto.at(q);
      const bool on = std::find(front.begin(), front.end(), i) != front.end();
      o << fmt::format(" {:>9}", percent(r.errors.at(q)) + (on ? "*" : " "));
    }
    o << (p.reference.row && *p.reference.row == i ? "  reference" : "") << '\n';
  }
  o << "errors relative to the reference; * on the Pareto front of |error| against CPU time\n";
  if (p.reference.row) {
    const PriceRow& ref = p.rows[*p.reference.row];
    o << fmt::format("reference: {} / {} / {} at dt = {:.4g} ms\n", ref.model, ref.structure, ref.contact_law,
                     1e3 * ref.dt_s);
    o << fmt::format("{:<36} {:>14} {:>22} {:>10}\n", "quantity", "value", "reference's own error", "order");
    for (std::string_view qv : price_quantities()) {
      const std::string q(qv);
      const auto v = ref.values.count(q) ? ref.values.at(q) : std::nullopt;
      if (!v) continue;
      const auto it = p.reference.richardson.find(q);
      std::string est = "-", order = "-";
      if (it != p.reference.richardson.end()) {
        const RichardsonEstimate& e = it->second;
        est = e.asymptotic ? percent(e.error)
                           : "not asymptotic" + (e.last_change ? " (" + percent(e.last_change) + " from 2h)" : "");
        if (e.order) order = fmt::format("{:.2f}", *e.order);
      }
      o << fmt::format("{:<36} {:>14.6g} {:>22} {:>10}\n", q, *v, est, order);
    }
  } else {
    o << "no run of the reference rung is ok: no errors\n";
  }
  o << "cheapest within 1 % / 5 %:\n";
  for (std::string_view qv : price_quantities()) {
    const std::string q(qv);
    const auto name = [&](const std::optional<std::size_t>& i) {
      if (!i) return std::string("-");
      const PriceRow& r = p.rows[*i];
      return fmt::format("{} / {} / {} {:.4g} ms ({:.3g} s)", r.model, r.structure, r.contact_law, 1e3 * r.dt_s, r.cpu_s);
    };
    const auto& c1 = p.cheapest_1pct.at(q);
    const auto& c5 = p.cheapest_5pct.at(q);
    if (!c1 && !c5) continue;
    o << fmt::format("  {:<34} {} | {}\n", q, name(c1), name(c5));
  }
  o << fmt::format("{} runs on {} thread{} in {:.3g} s wall\n", p.rows.size(), p.threads, p.threads == 1 ? "" : "s",
                   p.wall_s);
  return o.str();
}

std::string csv_header(bool with_job) {
  std::string h = with_job ? "job," : "";
  h += "model,structure,contact_law,modes,dt_s,status,steps,cpu_s,cpu_predicted_s,wall_s,reference";
  for (std::string_view q : price_quantities()) h += fmt::format(",{0},error_{0},pareto_{0}", q);
  return h + ",warnings\n";
}

std::string csv_value(std::optional<double> v) { return v && std::isfinite(*v) ? fmt::format("{:.17g}", *v) : ""; }

std::string price_csv(const PriceReport& p, const std::string& job) {
  std::ostringstream o;
  for (std::size_t i = 0; i < p.rows.size(); ++i) {
    const PriceRow& r = p.rows[i];
    if (!job.empty()) o << job << ',';
    o << fmt::format("{},{},{},{},{:.17g},{},{},{:.6g},{},{:.6g},{}", r.model, r.structure, r.contact_law,
                     r.modes ? std::to_string(*r.modes) : "", r.dt_s, r.status, r.steps, r.cpu_s,
                     csv_value(r.cpu_predicted_s), r.wall_s, p.reference.row && *p.reference.row == i ? 1 : 0);
    for (std::string_view qv : price_quantities()) {
      const std::string q(qv);
      const auto v = r.values.count(q) ? r.values.at(q) : std::nullopt;
      const auto e = r.errors.count(q) ? r.errors.at(q) : std::nullopt;
      const auto& front = p.pareto.at(q);
      o << ',' << csv_value(v) << ',' << csv_value(e) << ','
        << (std::find(front.begin(), front.end(), i) != front.end() ? 1 : 0);
    }
    o << ',' << fmt::format("{}", fmt::join(r.warnings, ";")) << '\n';
  }
  return o.str();
}

PriceOptions options_for(const Scene& scene, int threads) {
  PriceOptions o;
  o.threads = threads;
  if (scene.structure->num_dofs() <= kMaxDofsForDeckFrequencies) {  // as vsi simulate
    const DeckFrequencies f = deck_frequencies(*scene.structure);
    o.f0_hz = f.f0_hz;
    o.f3_hz = f.f3_hz;
  }
  return o;
}

PriceReport price_of(Scene scene, int threads) {
  // The filtered deck acceleration needs every step.
  scene.analysis.history_stride = 1;
  return price_scene(scene, options_for(scene, threads));
}

bool reference_ok(const PriceReport& p) { return p.reference.row.has_value(); }

int price_scene_file(const PriceArgs& args) {
  const Scene scene = load_scene(args.scene_file);
  const PriceReport p = [&] {
    try {
      return price_of(scene, args.threads);
    } catch (const InputError& e) {
      throw e.with_file(args.scene_file);
    }
  }();
  if (args.format == "json") {
    ordered_json out;
    out["scene"] = args.scene_file;
    const ordered_json body = price_json(p);
    for (const auto& [k, v] : body.items()) out[k] = v;
    std::cout << out.dump(2) << '\n';
  } else if (args.format == "csv") {
    std::cout << csv_header(false) << price_csv(p, "");
  } else {
    std::cout << "vsi price " << scheduler::terminal_safe(args.scene_file) << '\n' << price_table(p);
  }
  return reference_ok(p) ? kExitOk : kExitRuntimeFailure;
}

int price_study(const PriceArgs& args) {
  // Writable: the rows are stored for the report's accuracy-price chart.
  const auto opened = open_study(args.db, args.study_id, scheduler::OpenMode::kExisting);
  if (!opened) return kExitInvalidInput;
  scheduler::Database* const db = opened->db.get();
  const std::string* const id = &opened->id;
  const std::vector<scheduler::SampledJob> sample = scheduler::price_sample(*db, *id, args.jobs);
  ordered_json jobs = ordered_json::array();
  bool all_ok = true;
  if (args.format == "csv") std::cout << csv_header(true);
  for (const scheduler::SampledJob& s : sample) {
    const PriceReport p = price_of(scheduler::load_job_scene(*db, s.job.id), args.threads);
    scheduler::store_price_rows(*db, *id, s.job.id, p);
    all_ok = all_ok && reference_ok(p);
    if (args.format == "json") {
      ordered_json j;
      j["job"] = s.job.id;
      j["train"] = s.job.train;
      j["speed_kmh"] = s.job.speed_kmh;
      j["irregularity"] = s.job.irregularity;
      j["why"] = s.reasons;
      j["price"] = price_json(p);
      jobs.push_back(j);
    } else if (args.format == "csv") {
      std::cout << price_csv(p, s.job.id) << std::flush;
    } else {
      std::string why;
      for (const std::string& r : s.reasons) why += (why.empty() ? "" : ", ") + r;
      std::cout << fmt::format("job {}: {} at {:g} km/h, {} ({})\n", s.job.id.substr(0, 12),
                               scheduler::terminal_safe(s.job.train), s.job.speed_kmh,
                               scheduler::terminal_safe(s.job.irregularity), why)
                << price_table(p) << '\n'
                << std::flush;
    }
  }
  if (args.format == "json") std::cout << ordered_json{{"study", *id}, {"jobs", jobs}}.dump(2) << '\n';
  return all_ok ? kExitOk : kExitRuntimeFailure;
}

}  // namespace

PriceCommand::PriceCommand(CLI::App& app) {
  price_ = app.add_subcommand(
      "price", "What accuracy costs: every rung of the fidelity ladder at the policy's dt x 4, x 2, x 1, / 2, / 4, "
               "timed, with the error of each key quantity against the most accurate run");
  price_->add_option("scene", args_.scene_file, "Scene file (JSON)");
  price_->add_option("--db", args_.db, "Study database (SQLite file), with --study");
  price_->add_option("--study", args_.study_id, "Study id (a unique prefix): price its governing cases and store the rows in the "
                                                    "database for the accuracy-price chart of vsi report");
  price_->add_option("--jobs", args_.jobs, "With --study: price this many jobs (governing cases first, then spread)")
      ->check(CLI::Range(0, 1000));
  price_->add_option("--format", args_.format, "Output: table (default), json or csv")
      ->check(CLI::IsMember({"table", "json", "csv"}));
  price_->add_option("--threads", args_.threads, "Runs in parallel (default 1)")->check(CLI::Range(1, 256));
}

std::optional<int> PriceCommand::run_parsed() const {
  if (!price_->parsed()) return std::nullopt;
  return price_command(args_);
}

int price_command(const PriceArgs& args) {
  const bool scene = !args.scene_file.empty(), study = !args.study_id.empty();
  if (scene == study || (study && args.db.empty()) || (scene && !args.db.empty())) {
    std::cerr << "error: vsi price takes a scene file, or --db F --study ID\n";
    return kExitInvalidInput;
  }
  scheduler::single_threaded_blas();
  return scene ? price_scene_file(args) : price_study(args);
}

}  // namespace railvsi::cli
