#include "query/price_figures.hpp"

#include <cmath>
#include <map>

#include <fmt/format.h>

#include "query/price_rows.hpp"

namespace railvsi::scheduler {
namespace {

std::string job_label(Database& db, const std::string& job_id) {
  Statement s = db.prepare("SELECT train, speed_kmh, irregularity FROM jobs WHERE id = ?");
  if (!s.bind(1, job_id).step()) return job_id.substr(0, 12);
  return fmt::format("{} at {:g} km/h, {}", s.text(0), s.real(1), s.text(2));
}

std::string rung_label(const StoredPriceRow& r) { return r.model + " / " + r.structure + " / " + r.contact_law; }

}  // namespace

void add_price_figures(Database& db, const std::string& study_id, ComplianceReport& report) {
  const std::vector<StoredPriceRow> rows = read_price_rows(db, study_id);
  if (rows.empty()) {
    // The store's path is left out: a merged store reports as one run would.
    report.price_note = fmt::format("No accuracy-price chart: run vsi price --db F --study {} on this database (it "
                                    "re-runs the governing cases on every rung and time step and stores the runs), "
                                    "then vsi report again.",
                                    study_id.substr(0, 12));
    return;
  }
  report.price_note =
      "From vsi price --db --study: each governing case re-run on every rung of the fidelity ladder at the time-step "
      "policy's dt x 4, x 2, x 1, / 2, / 4. Each point is one run: its CPU time alone (with the setup it shares) "
      "against |error| of the quantity relative to the reference run (the finest step of the most complete rung), "
      "both on log axes; errors below 1e-6, the reference's own 0 among them, sit on the bottom axis.";
  // In the order of the rows: jobs, then runs; charts by job and quantity.
  std::vector<std::pair<std::string, std::string>> order;
  std::map<std::pair<std::string, std::string>, std::vector<const StoredPriceRow*>> groups;
  for (const StoredPriceRow& r : rows) {
    if (r.status != "ok" || !r.error || !(r.cpu_s > 0.0)) continue;
    const auto key = std::pair{r.job_id, r.quantity};
    auto [it, fresh] = groups.try_emplace(key);
    if (fresh) order.push_back(key);
    it->second.push_back(&r);
  }
  std::map<std::string, std::string> labels;
  for (const auto& key : order) {
    const auto& [job, quantity] = key;
    if (!labels.count(job)) labels[job] = job_label(db, job);
    PriceFigure f;
    f.chart.title = quantity + ": " + labels[job];
    const StoredPriceRow* cheapest_1 = nullptr;
    const StoredPriceRow* cheapest_5 = nullptr;
    for (const StoredPriceRow* r : groups.at(key)) {
      f.chart.points.push_back({rung_label(*r), r->dt_s, r->cpu_s, *r->error, r->pareto, r->reference});
      const double e = std::abs(*r->error);
      if (e <= 0.01 && (!cheapest_1 || r->cpu_s < cheapest_1->cpu_s)) cheapest_1 = r;
      if (e <= 0.05 && (!cheapest_5 || r->cpu_s < cheapest_5->cpu_s)) cheapest_5 = r;
    }
    const auto name = [&](const StoredPriceRow* r) {
      return r ? fmt::format("{} at {:g} ms ({:.3g} s)", rung_label(*r), 1e3 * r->dt_s, r->cpu_s) : std::string("none");
    };
    f.caption = fmt::format("Accuracy against CPU time of {} for {}: {} runs. Cheapest within 1 %: {}; within 5 %: {}.",
                            quantity, labels[job], f.chart.points.size(), name(cheapest_1), name(cheapest_5));
    report.price_charts.push_back(std::move(f));
  }
}

}  // namespace railvsi::scheduler
