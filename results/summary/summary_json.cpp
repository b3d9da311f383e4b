#include "summary/summary_json.hpp"

#include <cmath>

namespace railvsi {
namespace {

using nlohmann::ordered_json;

// A NaN printed as a number would be silent garbage: null says "no value".
ordered_json number(double v) { return std::isfinite(v) ? ordered_json(v) : ordered_json(nullptr); }
ordered_json optional_number(const std::optional<double>& v) { return v ? number(*v) : ordered_json(nullptr); }

ordered_json deck(const RunSummary& s) {
  ordered_json points = ordered_json::array();
  for (const PointSummary& p : s.points)
    points.push_back({{"name", p.name},
                      {"x_m", number(p.x_m)},
                      {"max_abs_displacement_m", number(p.max_abs_displacement_m)},
                      {"max_abs_acceleration_mps2", number(p.max_abs_acceleration_mps2)},
                      {"max_abs_bending_moment_Nm", optional_number(p.max_abs_bending_moment_Nm)},
                      {"max_abs_shear_force_N", optional_number(p.max_abs_shear_force_N)}});
  ordered_json out = {{"max_abs_displacement_m", number(s.max_abs_displacement_m)},
                      {"max_abs_acceleration_mps2", number(s.max_abs_acceleration_mps2)},
                      {"points", points}};
  if (!s.section_forces_note.empty()) out["section_forces_note"] = s.section_forces_note;
  // EN 1990 A2.4.4.2.2, between the track's two rail lines; null with the
  // reason on a plane model.
  out["twist"] = s.max_abs_deck_twist_m
                     ? ordered_json{{"max_abs_mm_per_3m", number(1e3 * *s.max_abs_deck_twist_m)},
                                    {"x_m", number(s.deck_twist_x_m)}}
                     : ordered_json{{"max_abs_mm_per_3m", nullptr}, {"note", s.deck_twist_note}};
  return out;
}

// Beam decks: reaction and end rotation per support (empty otherwise, the
// deck's section_forces_note says why).
ordered_json supports(const RunSummary& s) {
  ordered_json out = ordered_json::array();
  for (const SupportSummary& p : s.supports)
    out.push_back({{"name", p.name},
                   {"x_m", number(p.x_m)},
                   {"max_reaction_N", number(p.max_reaction_N)},
                   {"max_abs_rotation_rad", number(p.max_abs_rotation_rad)}});
  return out;
}

ordered_json wheels(const RunSummary& s, bool moving_forces) {
  const auto value = [&](double v) { return moving_forces ? ordered_json(nullptr) : number(v); };
  return {{"min_contact_force_N", value(s.min_contact_force_N)},
          {"max_unloading_ratio", value(s.max_unloading_ratio)},
          {"contact_loss_s", value(s.contact_loss_s)}};
}

}  // namespace

ordered_json warnings_json(const std::vector<RunWarning>& warnings) {
  ordered_json out = ordered_json::array();
  for (const RunWarning& w : warnings) {
    ordered_json item = {{"code", w.code}, {"message", w.message}};
    if (w.t_s) item["t_s"] = number(*w.t_s);
    if (w.wheel) item["wheel"] = *w.wheel;
    if (w.factor) item["factor"] = number(*w.factor);
    out.push_back(std::move(item));
  }
  return out;
}

namespace {

ordered_json ignores_json(const std::vector<FidelityRecord::Ignored>& ignores) {
  ordered_json out = ordered_json::array();
  for (const auto& i : ignores) out.push_back({{"what", i.what}, {"why", i.why}});
  return out;
}

}  // namespace

ordered_json fidelity_json(const FidelityRecord& s) {
  return {{"model", s.model},
          {"contact_law", s.contact_law},
          {"unilateral", s.unilateral},
          {"solver_path", s.solver_path},
          {"structure_backend", s.structure_backend},
          {"structure_dofs", s.structure_dofs},
          {"vehicle_dofs", s.vehicle_dofs},
          {"contacts", s.contacts},
          {"hht_alpha", number(s.hht_alpha)},
          {"hht_beta", number(s.hht_beta)},
          {"hht_gamma", number(s.hht_gamma)},
          {"rung", s.rung},
          {"chosen_by", s.chosen_by},
          {"dt_s", number(s.dt_s)},
          {"modes", s.modes},
          {"modal_cutoff_hz", s.modes > 0 ? number(s.modal_cutoff_hz) : ordered_json(nullptr)},
          {"static_correction", s.modes > 0 ? ordered_json(s.static_correction) : ordered_json(nullptr)},
          {"reasons", s.reasons},
          {"ignores", ignores_json(s.ignores)},
          {"escalation", s.escalation.empty() ? ordered_json(nullptr) : ordered_json(s.escalation)}};
}

ordered_json summary_json(const Result& result, bool moving_forces) {
  const RunSummary& s = result.summary;
  ordered_json out;
  out["status"] = std::string(result.status.name());
  if (!result.status.ok()) out["message"] = result.status.message();
  out["deck"] = deck(s);
  out["supports"] = supports(s);
  out["wheels"] = wheels(s, moving_forces);
  out["vehicles"] = {{"max_abs_carbody_acceleration_mps2",
                      moving_forces ? ordered_json(nullptr) : number(s.max_abs_carbody_acceleration_mps2)}};
  out["run"] = {{"steps", s.steps},
                {"dt_s", number(s.dt_s)},
                {"newton_iterations", s.newton_iterations},
                {"wall_s", number(s.wall_s)},
                {"energy_residual", number(s.energy_residual)},
                {"warnings", warnings_json(s.warnings)},
                {"fidelity", fidelity_json(s.fidelity)}};
  return out;
}

}  // namespace railvsi
