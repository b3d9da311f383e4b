#include "price/dt_self_check.hpp"

#include <cmath>

#include <fmt/format.h>

#include "price/price_analysis.hpp"

namespace railvsi {

std::map<std::string, std::optional<double>> key_quantity_values(const JobEnvelopes& e) {
  return {{"deck_displacement_m", e.max_abs_displacement_m},
          {"deck_acceleration_mps2", e.max_abs_acceleration_mps2},
          {"deck_acceleration_unfiltered_mps2", e.max_abs_acceleration_unfiltered_mps2},
          {"min_contact_force_N", e.min_contact_force_N},
          {"unloading_ratio", e.max_unloading_ratio},
          {"contact_loss_s", e.max_contact_loss_s},
          {"carbody_acceleration_mps2", e.max_abs_carbody_acceleration_mps2}};
}

bool DtSelfCheck::any_above() const {
  for (const DtCheckRow& r : rows)
    if (r.above_tolerance) return true;
  return false;
}

DtSelfCheck dt_self_check(const JobEnvelopes& at_dt, const JobEnvelopes& at_half_dt, double dt_s, double half_dt_s,
                          double tolerance) {
  DtSelfCheck check;
  check.dt_s = dt_s;
  check.half_dt_s = half_dt_s;
  check.tolerance = tolerance;
  const auto coarse = key_quantity_values(at_dt), fine = key_quantity_values(at_half_dt);
  for (const std::string_view q : price_quantities()) {
    DtCheckRow row;
    row.quantity = std::string(q);
    row.value = coarse.at(row.quantity);
    row.half_dt_value = fine.at(row.quantity);
    if (!row.value && !row.half_dt_value) continue;
    row.relative_change = relative_error(row.value, row.half_dt_value);
    // A value one run has and the other lacks, or a zero that becomes
    // nonzero (a contact loss that appears at dt/2), is a change of the
    // answer with no relative size: flagged, never passed.
    row.above_tolerance = row.relative_change ? std::abs(*row.relative_change) > tolerance : true;
    check.rows.push_back(std::move(row));
  }
  return check;
}

std::vector<RunWarning> dt_self_check_warnings(const DtSelfCheck& check) {
  std::vector<RunWarning> out;
  const auto text = [](const std::optional<double>& v) { return v ? fmt::format("{:.6g}", *v) : std::string("none"); };
  for (const DtCheckRow& r : check.rows) {
    if (!r.above_tolerance) continue;
    RunWarning w;
    w.code = "dt_self_check";
    w.message = r.relative_change
                    ? fmt::format("{} changes {:+.2f} % when dt is halved ({} at dt {:.4g} s, {} at {:.4g} s), more "
                                  "than the tolerance {:g} %: the value is not converged in dt; give a smaller dt_s",
                                  r.quantity, 100.0 * *r.relative_change, text(r.value), check.dt_s,
                                  text(r.half_dt_value), check.half_dt_s, 100.0 * check.tolerance)
                    : fmt::format("{} is {} at dt {:.4g} s and {} at {:.4g} s: the value is not converged in dt; "
                                  "give a smaller dt_s",
                                  r.quantity, text(r.value), check.dt_s, text(r.half_dt_value), check.half_dt_s);
    w.factor = r.relative_change ? std::optional<double>(std::abs(*r.relative_change) / check.tolerance) : std::nullopt;
    out.push_back(std::move(w));
  }
  return out;
}

nlohmann::ordered_json dt_self_check_json(const DtSelfCheck& check) {
  using nlohmann::ordered_json;
  const auto number = [](const std::optional<double>& v) {
    return v && std::isfinite(*v) ? ordered_json(*v) : ordered_json(nullptr);
  };
  ordered_json rows = ordered_json::array();
  for (const DtCheckRow& r : check.rows)
    rows.push_back({{"quantity", r.quantity},
                    {"value", number(r.value)},
                    {"half_dt_value", number(r.half_dt_value)},
                    {"relative_change", number(r.relative_change)},
                    {"above_tolerance", r.above_tolerance}});
  return {{"dt_s", check.dt_s},
          {"half_dt_s", check.half_dt_s},
          {"tolerance", check.tolerance},
          {"converged", !check.any_above()},
          {"quantities", std::move(rows)}};
}

}  // namespace railvsi
