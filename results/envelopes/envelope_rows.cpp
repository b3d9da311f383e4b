#include "envelopes/envelope_rows.hpp"

#include <algorithm>

namespace railvsi {

const std::vector<EnvelopeQuantity>& envelope_quantities() {
  static const std::vector<EnvelopeQuantity> all = {
      {"deck_displacement_m", Extreme::kMax, "max |vertical deck displacement| from the unloaded equilibrium"},
      {"deck_acceleration_mps2", Extreme::kMax,
       "max |vertical deck acceleration| after the EN 1990 A2.4.4.2 low-pass filter"},
      {"deck_acceleration_unfiltered_mps2", Extreme::kMax, "max |vertical deck acceleration|, all frequencies"},
      {"bending_moment_Nm", Extreme::kMax, "max |bending moment| at the output point's section (beam decks)"},
      {"shear_force_N", Extreme::kMax, "max |shear force| on either side of the output point's section (beam decks)"},
      {"support_reaction_N", Extreme::kMax, "largest support reaction from traffic, upward (beam decks)"},
      {"support_rotation_rad", Extreme::kMax, "max |deck end rotation| at the support (beam decks)"},
      {"deck_twist_mm_per_3m", Extreme::kMax,
       "max |deck twist| over 3 m between the track's two rail lines (EN 1990 A2.4.4.2.2), mm"},
      {"min_contact_force_N", Extreme::kMin, "smallest wheel contact force in the evaluation window"},
      {"unloading_ratio", Extreme::kMax, "wheel unloading (Q0 - Qmin)/Q0 in the evaluation window, 1 = contact lost"},
      {"contact_loss_s", Extreme::kMax, "time a wheel spent without contact in the evaluation window"},
      {"carbody_acceleration_mps2", Extreme::kMax, "max |car-body vertical acceleration| in the evaluation window"},
      {"newton_iterations", Extreme::kMax, "Newton iterations of the whole run"},
      {"max_newton_iterations_in_step", Extreme::kMax, "most Newton iterations in one step"},
  };
  return all;
}

std::optional<Extreme> extreme_of(std::string_view quantity) {
  const auto& all = envelope_quantities();
  const auto it = std::find_if(all.begin(), all.end(), [&](const EnvelopeQuantity& q) { return q.name == quantity; });
  if (it == all.end()) return std::nullopt;
  return it->extreme;
}

std::vector<EnvelopeRow> envelope_rows(const JobEnvelopes& e) {
  std::vector<EnvelopeRow> rows;
  const auto add = [&](std::string_view quantity, const std::string& location, std::optional<double> value) {
    rows.push_back({std::string(quantity), location, value});
  };
  for (const PointEnvelope& p : e.points) add("deck_displacement_m", p.name, p.max_abs_displacement_m);
  add("deck_displacement_m", "", e.max_abs_displacement_m);
  for (const PointEnvelope& p : e.points) add("deck_acceleration_mps2", p.name, p.max_abs_acceleration_mps2);
  add("deck_acceleration_mps2", "", e.max_abs_acceleration_mps2);
  for (const PointEnvelope& p : e.points)
    add("deck_acceleration_unfiltered_mps2", p.name, p.max_abs_acceleration_unfiltered_mps2);
  add("deck_acceleration_unfiltered_mps2", "", e.max_abs_acceleration_unfiltered_mps2);
  // Section forces: only for a beam deck (values at some point or support).
  const auto per_point = [&](std::string_view quantity, std::optional<double> PointEnvelope::*field) {
    std::optional<double> overall;
    bool any = false;
    for (const PointEnvelope& p : e.points)
      if (p.*field) {
        any = true;
        add(quantity, p.name, p.*field);
        overall = std::max(overall.value_or(*(p.*field)), *(p.*field));
      }
    if (any) add(quantity, "", overall);
  };
  per_point("bending_moment_Nm", &PointEnvelope::max_abs_bending_moment_Nm);
  per_point("shear_force_N", &PointEnvelope::max_abs_shear_force_N);
  const auto per_support = [&](std::string_view quantity, std::optional<double> SupportEnvelope::*field) {
    if (e.supports.empty()) return;
    std::optional<double> overall;
    bool hole = false;
    for (const SupportEnvelope& s : e.supports) {
      add(quantity, s.name, s.*field);
      if (!(s.*field)) hole = true;
      else overall = std::max(overall.value_or(*(s.*field)), *(s.*field));
    }
    add(quantity, "", hole ? std::nullopt : overall);  // a maximum with a missing member is not the maximum
  };
  per_support("support_reaction_N", &SupportEnvelope::max_reaction_N);
  per_support("support_rotation_rad", &SupportEnvelope::max_abs_rotation_rad);
  // Only a structure with two rail lines has a twist (a plane model: no row).
  if (e.deck_twist_applicable) add("deck_twist_mm_per_3m", "", e.max_abs_deck_twist_mm_per_3m);
  if (!e.wheels.empty()) {
    // Per wheel only for wheels inside the evaluation window: the others have no values.
    const auto per_wheel = [&](std::string_view quantity, std::optional<double> WheelEnvelope::*field) {
      for (const WheelEnvelope& w : e.wheels)
        if (w.evaluated) add(quantity, w.name, w.*field);
    };
    per_wheel("min_contact_force_N", &WheelEnvelope::min_force_N);
    add("min_contact_force_N", "", e.min_contact_force_N);
    per_wheel("unloading_ratio", &WheelEnvelope::unloading_ratio);
    add("unloading_ratio", "", e.max_unloading_ratio);
    per_wheel("contact_loss_s", &WheelEnvelope::contact_loss_s);
    add("contact_loss_s", "", e.max_contact_loss_s);
    add("carbody_acceleration_mps2", "", e.max_abs_carbody_acceleration_mps2);
  }
  add("newton_iterations", "", static_cast<double>(e.newton_iterations));
  add("max_newton_iterations_in_step", "", static_cast<double>(e.max_newton_iterations_in_step));
  return rows;
}

}  // namespace railvsi
