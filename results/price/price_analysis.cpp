#include "price/price_analysis.hpp"

#include <algorithm>
#include <cmath>

namespace railvsi {

const std::vector<std::string_view>& price_quantities() {
  static const std::vector<std::string_view> names = {
      "deck_displacement_m", "deck_acceleration_mps2", "deck_acceleration_unfiltered_mps2", "min_contact_force_N",
      "unloading_ratio",     "contact_loss_s",         "carbody_acceleration_mps2"};
  return names;
}

RichardsonEstimate richardson_estimate(std::optional<double> v1, std::optional<double> v2, std::optional<double> v4) {
  RichardsonEstimate e;
  if (!v1 || !v2) return e;
  if (*v1 != 0.0) e.last_change = (*v2 - *v1) / *v1;
  if (!v4) return e;
  const double d1 = *v2 - *v1, d2 = *v4 - *v2;
  const double roundoff = 1e-12 * std::abs(*v1);
  if (std::abs(d1) <= roundoff && std::abs(d2) <= roundoff) {
    e.asymptotic = true;
    e.error = 0.0;
    return e;
  }
  if (!(d1 * d2 > 0.0)) return e;
  const double r = d2 / d1;
  e.order = std::log2(r);
  if (r < kRichardsonMinRatio || r > kRichardsonMaxRatio) return e;
  const double v_star = *v1 - d1 / (r - 1.0);
  if (v_star == 0.0) return e;
  e.asymptotic = true;
  e.error = (*v1 - v_star) / v_star;
  return e;
}

std::optional<double> relative_error(std::optional<double> v, std::optional<double> v_ref) {
  if (!v || !v_ref) return std::nullopt;
  if (*v_ref != 0.0) return (*v - *v_ref) / *v_ref;
  if (*v == 0.0) return 0.0;
  return std::nullopt;
}

PriceReference price_errors(std::vector<PriceRow>& rows) {
  PriceReference ref;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    if (!rows[i].ok()) continue;
    if (!ref.row) {
      ref.row = i;
      continue;
    }
    const PriceRow& best = rows[*ref.row];
    if (rows[i].rung > best.rung || (rows[i].rung == best.rung && rows[i].dt_s < best.dt_s)) ref.row = i;
  }
  for (PriceRow& r : rows) r.errors.clear();
  if (!ref.row) return ref;
  const PriceRow reference = rows[*ref.row];
  for (PriceRow& r : rows) {
    for (std::string_view q : price_quantities()) {
      std::optional<double>& err = r.errors[std::string(q)];
      const auto v = r.values.find(std::string(q));
      const auto v_ref = reference.values.find(std::string(q));
      if (!r.ok() || v == r.values.end() || v_ref == reference.values.end()) continue;
      err = relative_error(v->second, v_ref->second);
    }
  }
  // The reference rung's runs at 2h and 4h.
  const auto at = [&](double dt_s) -> std::optional<std::size_t> {
    for (std::size_t i = 0; i < rows.size(); ++i)
      if (rows[i].rung == reference.rung && rows[i].ok() &&
          std::abs(rows[i].dt_s - dt_s) <= 1e-9 * dt_s)
        return i;
    return std::nullopt;
  };
  const auto r2 = at(2.0 * reference.dt_s), r4 = at(4.0 * reference.dt_s);
  if (r2 && r4) ref.richardson_rows = {*ref.row, *r2, *r4};
  for (std::string_view q : price_quantities()) {
    const std::string key(q);
    const auto value = [&](std::optional<std::size_t> i) -> std::optional<double> {
      if (!i) return std::nullopt;
      const auto it = rows[*i].values.find(key);
      return it == rows[*i].values.end() ? std::nullopt : it->second;
    };
    if (!value(ref.row)) continue;
    ref.richardson[key] = richardson_estimate(value(ref.row), value(r2), value(r4));
  }
  return ref;
}

namespace {

// Rows with an error for the quantity, cheapest first (then the smaller error).
std::vector<std::size_t> by_cost(const std::vector<PriceRow>& rows, const std::string& q) {
  std::vector<std::size_t> idx;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const auto it = rows[i].errors.find(q);
    if (it != rows[i].errors.end() && it->second) idx.push_back(i);
  }
  const auto err = [&](std::size_t i) { return std::abs(*rows[i].errors.at(q)); };
  std::stable_sort(idx.begin(), idx.end(), [&](std::size_t a, std::size_t b) {
    return rows[a].cpu_s < rows[b].cpu_s || (rows[a].cpu_s == rows[b].cpu_s && err(a) < err(b));
  });
  return idx;
}

// Whether row i is smaller in |error| than a finer row of its own rung: its
// error is not monotone in dt there, and its small error is luck (rigid
// contact: the filtered deck acceleration moved 2.3 % for dt from 0.990 to
// 1.0005 ms), not a price to pay for.
bool lucky(const std::vector<PriceRow>& rows, std::size_t i, const std::string& q) {
  const double e = std::abs(*rows[i].errors.at(q));
  for (std::size_t j = 0; j < rows.size(); ++j) {
    if (j == i || rows[j].rung != rows[i].rung || rows[j].modes != rows[i].modes || !(rows[j].dt_s < rows[i].dt_s))
      continue;
    const auto it = rows[j].errors.find(q);
    if (it != rows[j].errors.end() && it->second && std::abs(*it->second) > e) return true;
  }
  return false;
}

}  // namespace

std::map<std::string, std::vector<std::size_t>> pareto_fronts(const std::vector<PriceRow>& rows) {
  std::map<std::string, std::vector<std::size_t>> fronts;
  for (std::string_view qv : price_quantities()) {
    const std::string q(qv);
    std::vector<std::size_t>& front = fronts[q];
    double best = INFINITY;
    for (std::size_t i : by_cost(rows, q)) {
      if (lucky(rows, i, q)) continue;
      const double e = std::abs(*rows[i].errors.at(q));
      if (e < best) {
        front.push_back(i);
        best = e;
      }
    }
  }
  return fronts;
}

std::map<std::string, std::optional<std::size_t>> cheapest_within(const std::vector<PriceRow>& rows,
                                                                   double tolerance) {
  std::map<std::string, std::optional<std::size_t>> out;
  for (std::string_view qv : price_quantities()) {
    const std::string q(qv);
    std::optional<std::size_t>& pick = out[q];
    for (std::size_t i : by_cost(rows, q))
      if (!lucky(rows, i, q) && std::abs(*rows[i].errors.at(q)) <= tolerance) {
        pick = i;
        break;
      }
  }
  return out;
}

}  // namespace railvsi
