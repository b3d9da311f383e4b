#include "query/price_rows.hpp"

#include <algorithm>
#include <cmath>

#include "core/unix_time.hpp"
#include "price/price_analysis.hpp"

namespace railvsi::scheduler {
namespace {

SqlValue optional_number(std::optional<double> v) {
  if (!v || !std::isfinite(*v)) return Null{};
  return *v;
}

bool on_front(const PriceReport& p, const std::string& quantity, std::size_t row) {
  const auto it = p.pareto.find(quantity);
  return it != p.pareto.end() && std::find(it->second.begin(), it->second.end(), row) != it->second.end();
}

}  // namespace

void store_price_rows(Database& db, const std::string& study_id, const std::string& job_id, const PriceReport& price) {
  const double now = unix_now_s();
  Transaction tx(db);
  db.prepare("DELETE FROM price_rows WHERE study_id = ? AND job_id = ?").bind(1, study_id).bind(2, job_id).run();
  Statement insert = db.prepare(
      "INSERT INTO price_rows (study_id, job_id, run, model, structure, contact_law, modes, dt_s, status, cpu_s, "
      "wall_s, reference, quantity, value, error, pareto, priced_at) "
      "VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?)");
  for (std::size_t i = 0; i < price.rows.size(); ++i) {
    const PriceRow& r = price.rows[i];
    for (std::string_view qv : price_quantities()) {
      const std::string q(qv);
      const auto value = r.values.count(q) ? r.values.at(q) : std::nullopt;
      const auto error = r.errors.count(q) ? r.errors.at(q) : std::nullopt;
      insert.reset();
      insert.bind(1, study_id).bind(2, job_id).bind(3, static_cast<int>(i)).bind(4, r.model).bind(5, r.structure);
      insert.bind(6, r.contact_law);
      if (r.modes)
        insert.bind(7, *r.modes);
      else
        insert.bind_null(7);
      insert.bind(8, r.dt_s).bind(9, r.status).bind(10, r.cpu_s).bind(11, r.wall_s);
      insert.bind(12, price.reference.row && *price.reference.row == i ? 1 : 0).bind(13, q);
      insert.bind(14, optional_number(value)).bind(15, optional_number(error));
      insert.bind(16, on_front(price, q, i) ? 1 : 0).bind(17, now);
      insert.run();
    }
  }
  tx.commit();
}

std::vector<StoredPriceRow> read_price_rows(Database& db, const std::string& study_id) {
  Statement s = db.prepare(
      "SELECT p.job_id, p.run, p.model, p.structure, p.contact_law, p.modes, p.dt_s, p.status, p.cpu_s, p.wall_s, "
      "p.reference, p.quantity, p.value, p.error, p.pareto FROM price_rows p "
      "LEFT JOIN study_jobs sj ON sj.study_id = p.study_id AND sj.job_id = p.job_id "
      "WHERE p.study_id = ? ORDER BY sj.position, p.job_id, p.run");
  s.bind(1, study_id);
  std::vector<StoredPriceRow> out;
  std::vector<std::pair<std::size_t, long>> key;  // (run in read order, quantity rank)
  const auto rank = [](const std::string& q) {
    const auto& all = price_quantities();
    return static_cast<long>(std::find(all.begin(), all.end(), q) - all.begin());
  };
  std::size_t group = 0;
  while (s.step()) {
    StoredPriceRow r;
    r.job_id = s.text(0);
    r.run = static_cast<int>(s.int64(1));
    r.model = s.text(2);
    r.structure = s.text(3);
    r.contact_law = s.text(4);
    if (!s.is_null(5)) r.modes = static_cast<int>(s.int64(5));
    r.dt_s = s.real(6);
    r.status = s.text(7);
    r.cpu_s = s.real(8);
    r.wall_s = s.real(9);
    r.reference = s.int64(10) != 0;
    r.quantity = s.text(11);
    r.value = s.optional_real(12);
    r.error = s.optional_real(13);
    r.pareto = s.int64(14) != 0;
    if (!out.empty() && (out.back().job_id != r.job_id || out.back().run != r.run)) ++group;
    key.emplace_back(group, rank(r.quantity));
    out.push_back(std::move(r));
  }
  // Within a run, the quantities in price_quantities() order.
  std::vector<std::size_t> order(out.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return key[a] < key[b]; });
  std::vector<StoredPriceRow> sorted;
  sorted.reserve(out.size());
  for (std::size_t i : order) sorted.push_back(std::move(out[i]));
  return sorted;
}

}  // namespace railvsi::scheduler
