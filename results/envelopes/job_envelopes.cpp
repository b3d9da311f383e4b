#include "envelopes/job_envelopes.hpp"

#include <algorithm>
#include <cmath>
#include <string_view>

#include <fmt/format.h>

#include "envelopes/code_filter.hpp"

namespace railvsi {
namespace {

// A non-finite number is never an envelope value: it is left out, named in
// the notes, and a run that called itself ok is not.
class FiniteOnly {
 public:
  explicit FiniteOnly(JobEnvelopes& e) : e_(e) {}
  std::optional<double> operator()(double v, std::string_view what) {
    if (std::isfinite(v)) return v;
    e_.notes.push_back(fmt::format("{}: non-finite value left out", what));
    if (e_.ok()) {
      e_.status = "diverged";
      e_.message = fmt::format("the run reported ok but produced a non-finite {}", what);
    }
    return std::nullopt;
  }

 private:
  JobEnvelopes& e_;
};

// The extreme over items that all have a value; absent when the set is
// empty or has a hole (a maximum with a missing member is not the maximum).
template <class Item, class Compare, class Counts>
std::optional<double> extreme(const std::vector<Item>& items, std::optional<double> Item::*field, Compare better,
                              Counts counts) {
  std::optional<double> out;
  for (const Item& it : items) {
    if (!counts(it)) continue;
    const std::optional<double>& v = it.*field;
    if (!v) return std::nullopt;
    if (!out || better(*v, *out)) out = v;
  }
  return out;
}

// Why the histories cannot give a filtered acceleration, or "" when they can.
std::string filter_obstacle(const Result& r, double dt_s, int history_stride, double cutoff_hz) {
  const Histories& h = r.histories;
  // The filter keeps content up to cutoff_hz; sampled below twice that,
  // the band it should keep is not in the histories (aliased into it).
  if (0.5 / dt_s < cutoff_hz)
    return fmt::format("the Nyquist frequency 1/(2 dt) = {:.3g} Hz is below the code cut-off {:.3g} Hz", 0.5 / dt_s,
                       cutoff_hz);
  if (history_stride != 1)
    return fmt::format("histories store every {}th step: decimation would alias content above {:.1f} Hz into the "
                       "filtered band; run with history_stride = 1",
                       history_stride, 0.5 / (dt_s * history_stride));
  if (h.deck_acceleration_mps2.size() != r.summary.points.size() || h.point_names.size() != r.summary.points.size())
    return "histories do not hold the deck acceleration of every output point";
  for (std::size_t p = 0; p < h.point_names.size(); ++p)
    if (h.point_names[p] != r.summary.points[p].name || h.deck_acceleration_mps2[p].size() != h.t_s.size())
      return fmt::format("histories of output point {} do not match the summary", r.summary.points[p].name);
  for (std::size_t k = 0; k < h.t_s.size(); ++k)
    if (std::abs(h.t_s[k] - static_cast<double>(k) * dt_s) > 1e-6 * dt_s)
      return fmt::format("histories are not sampled every dt = {} s (sample {} at t = {} s)", dt_s, k, h.t_s[k]);
  return "";
}

// filtered: the filtered maximum per output point, or null with the reason
// in obstacle.
JobEnvelopes envelopes_of(const Status& status, const RunSummary& s, double dt_s, double cutoff_hz,
                          const std::vector<double>* filtered, const std::string& obstacle) {
  JobEnvelopes e;
  e.status = std::string(status.name());
  e.message = status.message();
  FiniteOnly finite(e);
  const auto greater = [](double a, double b) { return a > b; };
  const auto less = [](double a, double b) { return a < b; };
  const auto every = [](const auto&) { return true; };

  // Deck.
  e.cutoff_hz = cutoff_hz;
  e.filter = code_filter_description(dt_s, cutoff_hz);
  if (!filtered) e.notes.push_back("filtered deck acceleration left out: " + obstacle);
  // The hybrid structure does not give the unfiltered deck acceleration
  // after a wheel's landing (rung_runner.cpp says why in its warning).
  const bool landed_on_hybrid = std::any_of(s.warnings.begin(), s.warnings.end(), [](const RunWarning& w) {
    return w.code == "unfiltered_acceleration_after_landing";
  });
  if (landed_on_hybrid)
    e.notes.push_back("unfiltered deck acceleration left out: a wheel lost contact on the hybrid structure (see the "
                      "run's warning)");
  for (std::size_t p = 0; p < s.points.size(); ++p) {
    const PointSummary& ps = s.points[p];
    PointEnvelope pe;
    pe.name = ps.name;
    pe.x_m = ps.x_m;
    pe.max_abs_displacement_m = finite(ps.max_abs_displacement_m, "deck displacement at " + ps.name);
    if (!landed_on_hybrid)
      pe.max_abs_acceleration_unfiltered_mps2 = finite(ps.max_abs_acceleration_mps2, "deck acceleration at " + ps.name);
    if (filtered) pe.max_abs_acceleration_mps2 = finite((*filtered)[p], "filtered deck acceleration at " + ps.name);
    if (ps.max_abs_bending_moment_Nm)
      pe.max_abs_bending_moment_Nm = finite(*ps.max_abs_bending_moment_Nm, "bending moment at " + ps.name);
    if (ps.max_abs_shear_force_N)
      pe.max_abs_shear_force_N = finite(*ps.max_abs_shear_force_N, "shear force at " + ps.name);
    e.points.push_back(std::move(pe));
  }
  for (const SupportSummary& ss : s.supports)
    e.supports.push_back({ss.name, ss.x_m, finite(ss.max_reaction_N, "reaction at " + ss.name),
                          finite(ss.max_abs_rotation_rad, "end rotation at " + ss.name)});
  if (!s.section_forces_note.empty()) e.notes.push_back("section forces left out: " + s.section_forces_note);
  if (s.max_abs_deck_twist_m) {
    e.deck_twist_applicable = true;
    e.max_abs_deck_twist_mm_per_3m = finite(1e3 * *s.max_abs_deck_twist_m, "deck twist");
  }
  e.max_abs_displacement_m = extreme(e.points, &PointEnvelope::max_abs_displacement_m, greater, every);
  e.max_abs_acceleration_mps2 = extreme(e.points, &PointEnvelope::max_abs_acceleration_mps2, greater, every);
  e.max_abs_acceleration_unfiltered_mps2 =
      extreme(e.points, &PointEnvelope::max_abs_acceleration_unfiltered_mps2, greater, every);

  // Wheels: only those inside the evaluation window have values.
  for (const WheelSummary& ws : s.wheels) {
    WheelEnvelope we;
    we.name = ws.name;
    we.evaluated = ws.evaluated;
    we.static_load_N = finite(ws.static_load_N, "static load of wheel " + ws.name);
    if (ws.evaluated) {
      we.min_force_N = finite(ws.min_force_N, "contact force of wheel " + ws.name);
      we.unloading_ratio = finite(ws.unloading_ratio, "unloading of wheel " + ws.name);
      we.contact_loss_s = finite(ws.contact_loss_s, "time without contact of wheel " + ws.name);
    }
    e.wheels.push_back(std::move(we));
  }
  const auto evaluated = [](const WheelEnvelope& w) { return w.evaluated; };
  e.max_unloading_ratio = extreme(e.wheels, &WheelEnvelope::unloading_ratio, greater, evaluated);
  e.max_contact_loss_s = extreme(e.wheels, &WheelEnvelope::contact_loss_s, greater, evaluated);
  e.min_contact_force_N = extreme(e.wheels, &WheelEnvelope::min_force_N, less, evaluated);
  if (!s.wheels.empty())  // a train of moving forces has neither wheels nor bodies
    e.max_abs_carbody_acceleration_mps2 = finite(s.max_abs_carbody_acceleration_mps2, "car-body acceleration");

  // Run: the summary's record, at the envelopes' dt, with times that can be stored.
  static_cast<RunRecord&>(e) = s;
  e.dt_s = dt_s;
  if (!std::isfinite(e.wall_s)) e.wall_s = 0.0;
  if (!std::isfinite(e.setup_s)) e.setup_s = 0.0;
  return e;
}

}  // namespace

JobEnvelopes compute_envelopes(const Result& result, double dt_s, int history_stride, double cutoff_hz) {
  const std::string obstacle = filter_obstacle(result, dt_s, history_stride, cutoff_hz);
  std::vector<double> filtered;
  if (obstacle.empty()) {
    const CodeFilter filter(dt_s, cutoff_hz);
    std::vector<double> workspace;
    for (const auto& a : result.histories.deck_acceleration_mps2) filtered.push_back(filter.max_abs_filtered(a, workspace));
  }
  return envelopes_of(result.status, result.summary, dt_s, cutoff_hz, obstacle.empty() ? &filtered : nullptr, obstacle);
}

JobEnvelopes compute_envelopes(const Status& status, const RunSummary& summary, double dt_s, double cutoff_hz,
                               const std::vector<double>* filtered_max, const std::string& obstacle) {
  return envelopes_of(status, summary, dt_s, cutoff_hz, filtered_max, obstacle);
}

}  // namespace railvsi
