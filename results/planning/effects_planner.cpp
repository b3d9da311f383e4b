#include "planning/effects_planner.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <fmt/format.h>

#include "core/sampled_peak.hpp"
#include "envelopes/code_filter.hpp"

namespace railvsi {

EffectsPlan plan_effects(const PlannerInput& in) {
  EffectsPlan plan;
  plan.code_frequency_hz = code_cutoff_hz(in.f0_hz, in.f3_hz);
  plan.modal_cutoff_hz = kModalCutoffMargin * plan.code_frequency_hz;
  Rung& r = plan.rung;
  if (in.load_model) {
    r.model = "moving_forces";
    r.contact_law = "none";
    plan.reasons.push_back("the train is a load model (axle forces): moving forces is its model");
    if (in.asks.wheel_unloading || in.asks.comfort)
      plan.reasons.push_back("wheel unloading and car-body comfort are asked but a load model has no wheels or car "
                             "bodies: those values stay absent");
  } else {
    r.model = "interaction";
    r.contact_law = "linear-hertz";
    r.unilateral = false;
    std::string why;
    if (in.asks.wheel_unloading) why += ", wheel unloading";
    if (in.asks.comfort) why += ", car-body comfort";
    if (in.irregularity) why += ", a track irregularity";
    plan.reasons.push_back(
        why.empty() ? "multibody vehicles: their suspensions change the deck response near resonance, so they run "
                      "with interaction"
                    : fmt::format("interaction answers what a force cannot ({})", why.substr(2)));
    const double fraction = in.asks.wheel_unloading ? kWheelEscalationFraction : kEscalationFraction;
    plan.reasons.push_back(fmt::format("Hertz linearized at the static load first; repeated with nonlinear "
                                       "unilateral Hertz if a contact force drops below {:g} % of its static load",
                                       100.0 * fraction));
    plan.escalate_below_fraction = fraction;
    if (in.asks.wheel_unloading) {
      plan.escalation_dt_factor = kWheelEscalationDtFactor;
      plan.reasons.push_back(fmt::format(
          "wheel unloading is asked: linearized Hertz's own error on dQ/Q was measured at 0.95-1.8 % beyond an "
          "unloading of {:g}, "
          "and unilateral Hertz's wheel values at the policy's dt were measured up to 3.2 % off the full model where "
          "a wheel unloads past half its load, within 1 % at {:g} x dt: the repeated run takes that step",
          1.0 - kWheelEscalationFraction, kWheelEscalationDtFactor));
    }
  }
  // The structure: modal unless its cut-off cannot be honoured.
  std::string fe_because;
  if (r.model == "interaction") {
    // Never the modes alone (kModalInteractionNotTrusted); hybrid where the
    // bridge's modes replace an interior much larger than the interface.
    const double hybrid_cutoff_hz = kHybridCutoffFactor * plan.code_frequency_hz;
    const bool interior = in.track_dofs > 0 && in.interior_dofs >= kHybridMinInteriorDofs &&
                          in.interior_dofs >= kHybridMinInteriorRatio * in.interface_dofs;
    if (interior && hybrid_cutoff_hz <= kHybridMaxCutoffHz) {
      r.structure = "hybrid";
      plan.modal_cutoff_hz = hybrid_cutoff_hz;
      plan.reasons.push_back(fmt::format(
          "hybrid structure: the track in FE ({} DOFs, its own damping), the bridge's {} DOFs off the track in their "
          "modes up to {:.1f} Hz = {:g} x the code frequency {:.1f} Hz (EN 1990 A2.4.4.2.1) with the {} DOFs the "
          "track bears on kept",
          in.track_dofs, in.interior_dofs, hybrid_cutoff_hz, kHybridCutoffFactor, plan.code_frequency_hz,
          in.interface_dofs));
      plan.ignores = rung_ignores(r, in.irregularity, plan.modal_cutoff_hz, plan.escalate_below_fraction);
      return plan;
    }
    fe_because = interior
                     ? fmt::format("the hybrid structure's cut-off, {:g} x the code frequency {:.1f} Hz = {:.1f} Hz, "
                                   "is above the {:g} Hz up to which it was measured (a short stiff span: it would keep "
                                   "most of the deck's modes); on the modes alone {}",
                                   kHybridCutoffFactor, plan.code_frequency_hz, hybrid_cutoff_hz, kHybridMaxCutoffHz,
                                   kModalInteractionNotTrusted)
                 : in.track_dofs > 0
                     ? fmt::format("the bridge has {} DOFs off the track against {} the track bears on: its modes "
                                   "would not make the hybrid structure cheaper (it needs at least {} and {:g} x as "
                                   "many); on the modes alone {}",
                                   in.interior_dofs, in.interface_dofs, kHybridMinInteriorDofs,
                                   kHybridMinInteriorRatio, kModalInteractionNotTrusted)
                     : kModalInteractionNotTrusted;
  } else if (!(in.f0_hz > 0.0) || !(in.f3_hz > 0.0))
    fe_because = "the deck frequencies f0 and f3 were not computed, so the modal cut-off max(30 Hz, 1.5 f0, f3) "
                 "cannot be set";
  else if (in.modes_below_cutoff < 0)
    fe_because = fmt::format("the modes below {:.1f} Hz were not counted", plan.modal_cutoff_hz);
  else if (in.modes_below_cutoff > kMaxModalModes)
    fe_because = fmt::format("{} modes lie below the modal cut-off {:.1f} Hz, more than the modal rung's {}",
                             in.modes_below_cutoff, plan.modal_cutoff_hz, kMaxModalModes);
  if (fe_because.empty()) {
    r.structure = "modal";
    plan.reasons.push_back(fmt::format(
        "modal structure: the {} modes up to {:.1f} Hz = {} x the code frequency {:.1f} Hz (max(30 Hz, 1.5 f0 = "
        "{:.2f} Hz, f3 = {:.2f} Hz), EN 1990 A2.4.4.2.1) with exact recurrence",
        in.modes_below_cutoff, plan.modal_cutoff_hz, kModalCutoffMargin, plan.code_frequency_hz, 1.5 * in.f0_hz,
        in.f3_hz));
  } else {
    r.structure = "fe";
    plan.reasons.push_back("FE structure: " + fe_because);
    plan.modal_cutoff_hz = 0.0;
  }
  plan.ignores = rung_ignores(r, in.irregularity, plan.modal_cutoff_hz, plan.escalate_below_fraction);
  return plan;
}

std::vector<FidelityRecord::Ignored> rung_ignores(const Rung& r, bool irregularity, double modal_cutoff_hz,
                                                  std::optional<double> escalate_below) {
  std::vector<FidelityRecord::Ignored> out;
  if (r.structure == "modal" && r.model == "moving_forces")
    out.push_back({fmt::format("the dynamic response of the structural modes above {:.1f} Hz", modal_cutoff_hz),
                   "the deck acceleration envelope keeps frequencies up to the code frequency (EN 1990 A2.4.4.2.1); "
                   "every mode up to the cut-off, with a 20 % margin, is kept, and the static response of the modes "
                   "above is added at the output points (mode-acceleration method)"});
  else if (r.structure == "modal")
    out.push_back({fmt::format("structural modes above {:.1f} Hz", modal_cutoff_hz),
                   "the deck acceleration envelope keeps frequencies up to the code frequency (EN 1990 A2.4.4.2.1); "
                   "every mode up to the cut-off, with a 20 % margin, is kept"});
  else if (r.structure == "hybrid")
    out.push_back({fmt::format("the dynamic response of the bridge's own modes above {:.1f} Hz",
                               modal_cutoff_hz),
                   "the track keeps its FE model and the constraint modes keep the static response of every bridge "
                   "mode left out; the deck acceleration envelope keeps frequencies up to the code "
                   "frequency (EN 1990 A2.4.4.2.1): also over a wheel's landing after a contact loss (filtered deck "
                   "acceleration within 0.3 % of FE, contact loss within 0.25 ms), where the unfiltered deck "
                   "acceleration was -29 % to +10 % off"});
  if (r.structure == "modal")
    out.push_back({"damping coupling between modes",
                   "each mode keeps its own ratio phi^T C phi / (2 omega), exact for Rayleigh damping"});
  if (r.model == "moving_forces") {
    out.push_back({"vehicle dynamics and wheel-rail contact",
                   "the train is given as axle forces (a load model such as HSLM, EN 1991-2 6.4.6.1.1)"});
    if (irregularity) out.push_back({"the track irregularity", "a moving force does not feel the rail profile"});
  } else if (r.contact_law == "linear-hertz") {
    const std::string what = r.unilateral ? "the nonlinearity of Hertz contact" : "the nonlinearity and unilaterality of Hertz contact";
    out.push_back({what, escalate_below ? fmt::format("no contact force fell below {:g} % of its static load (else the "
                                                      "run is repeated with nonlinear unilateral Hertz)",
                                                      100.0 * *escalate_below)
                                        : std::string("pinned: Hertz linearized at the static load, not checked")});
  }
  return out;
}

std::optional<std::string> escalation_reason(const RunSummary& summary, double fraction,
                                             std::optional<double> dt_factor) {
  for (const WheelSummary& w : summary.wheels) {
    if (!w.evaluated || !(w.static_load_N > 0.0)) continue;
    if (!(w.min_force_N >= fraction * w.static_load_N)) {
      std::string why = fmt::format("wheel {}: contact force down to {:.0f} N, below {:g} % of its static load {:.0f} "
                                    "N: linearized bilateral Hertz is not trusted that far, repeated with nonlinear "
                                    "unilateral Hertz",
                                    w.name, w.min_force_N, 100.0 * fraction, w.static_load_N);
      if (dt_factor && *dt_factor != 1.0)
        why += fmt::format(" at dt = {:.4g} s ({:g} x {:.4g} s) for the wheel values", *dt_factor * summary.dt_s,
                           *dt_factor, summary.dt_s);
      return why;
    }
  }
  return std::nullopt;
}

Rung escalated(const Rung& rung) {
  Rung r = rung;
  r.model = "interaction";
  r.contact_law = "hertz";
  r.unilateral = true;
  return r;
}

std::optional<Rung> next_rung(const Rung& rung) {
  if (rung.structure == "modal" || rung.structure == "hybrid") {
    Rung r = rung;
    r.structure = "fe";
    return r;
  }
  if (rung.model != "interaction" || (rung.contact_law == "hertz" && rung.unilateral)) return std::nullopt;
  return escalated(rung);
}

double modal_time_step_s(double code_frequency_hz, double tolerance, ModalPeaks peaks) {
  const bool refined = peaks != ModalPeaks::kSampled;
  const auto error = [&](double n) { return refined ? refined_peak_error(n) : sampled_peak_error(n); };
  // Both errors fall as n grows; for small pi / n they are (pi / n)^2 / 2
  // and 3/8 (pi / n)^4, so the search starts just below that estimate. A
  // tolerance so small that no double-precision dt honours it stops at 10^6
  // samples a period.
  const double estimate = refined ? std::numbers::pi * std::pow(0.375 / tolerance, 0.25)
                                                        : std::numbers::pi / std::sqrt(2.0 * tolerance);
  double n = std::max(3.0, std::floor(0.9 * std::min(estimate, 1e6)));
  while (n < 1e6 && error(n) > tolerance) n += 1.0;
  // The recurrence's own error, measured (effects_planner.hpp, kRefined).
  if (refined) n = std::max(n, std::ceil(16.0 * std::sqrt(0.01 / tolerance)));
  const double dt = 1.0 / (n * code_frequency_hz);
  const double scale = std::pow(10.0, std::floor(std::log10(dt)) - 2.0);
  return std::floor(dt / scale) * scale;
}

}  // namespace railvsi
