#include "planning/wheel_value_warnings.hpp"

#include <fmt/format.h>

#include "planning/effects_planner.hpp"
#include "planning/scene_plan.hpp"
#include "planning/time_step_policy.hpp"

namespace railvsi {
namespace {

// The evaluated wheel with the smallest force relative to its static load;
// in_contact: only wheels that never left the rail.
const WheelSummary* most_unloaded(const RunSummary& summary, bool in_contact) {
  const WheelSummary* worst = nullptr;
  for (const WheelSummary& w : summary.wheels) {
    if (!w.evaluated || !(w.static_load_N > 0.0)) continue;
    if (in_contact && (w.contact_loss_s > 0.0 || !(w.min_force_N > 0.0))) continue;
    if (!worst || w.min_force_N / w.static_load_N < worst->min_force_N / worst->static_load_N) worst = &w;
  }
  return worst;
}

std::string who_ran(const RunSummary& summary) {
  const FidelityRecord& f = summary.fidelity;
  const std::string law = f.contact_law == "linear-hertz"
                              ? fmt::format("{} linear Hertz", f.unilateral ? "unilateral" : "bilateral")
                              : f.contact_law == "hertz" ? std::string("nonlinear Hertz") : f.contact_law;
  const std::string by = f.chosen_by == "pinned"    ? "pinned in the scene"
                         : f.chosen_by == "planner" ? "the planner's"
                                                    : "the analysis as given";
  return fmt::format("{} on rung {} ({})", law, f.rung.empty() ? "interaction/fe" : f.rung, by);
}

}  // namespace

std::vector<RunWarning> wheel_value_warnings(const Scene& scene, const RunSummary& summary, double cutoff_hz) {
  std::vector<RunWarning> out;
  const std::string& law = summary.fidelity.contact_law;
  if (scene.train.is_moving_forces() || (law != "hertz" && law != "linear-hertz")) return out;
  if (!scene_asks(scene).wheel_unloading) return out;
  const double dt = scene.analysis.dt_s;
  const auto fraction = [](const WheelSummary& w) { return w.min_force_N / w.static_load_N; };

  // A wheel that leaves the rail has Q min = 0 and dQ/Q = 1 at any step, and
  // its contact-loss time is the track bound's (time_step_policy.hpp, bound
  // 4: over the 5 mm bump and FRA 1 it moved 0.0 % and 0.27 % from 0.25 to
  // 0.0625 ms). One that unloads far and stays on the rail does not
  // converge as fast: the step error of its Q min.
  if (const WheelSummary* w = most_unloaded(summary, true); w && fraction(*w) < kWheelEscalationFraction) {
    TimeStepPolicy policy;
    policy.hht = scene.analysis.hht;
    const TimeStepChoice c = choose_time_step(*scene.structure, scene.train, scene.speed_mps,
                                              scene.analysis.contact, 0.0, cutoff_hz, policy, scene.irregularity.get());
    // Above the policy's requirement dt_above_policy has said it already.
    const double wheel_dt = kWheelEscalationDtFactor * c.dt_s;
    if (dt <= c.required_dt_s * (1.0 + 1e-9) && dt > wheel_dt * (1.0 + 1e-9))
      out.push_back(
          {"wheel_values_dt",
           fmt::format("wheel {} fell to {:.0f} % of its static load without leaving the rail under {} at dt = "
                       "{:.3g} s, above {:g} x the policy's step {:.3g} s: where a wheel keeps less than {:g} % of "
                       "its load, the minimum contact force at the policy's step was measured up to +3.9 % off "
                       "(unconservative; ICE3 over a German high profile at 400 km/h, against dt/4) and within 1 % "
                       "at half of it (docs/accuracy-and-price.md \"Wheel values\"); run at dt <= {:.3g} s or with "
                       "\"fidelity\": \"auto\"",
                       w->name, 100.0 * fraction(*w), who_ran(summary), dt, kWheelEscalationDtFactor, c.dt_s,
                       100.0 * kWheelEscalationFraction, wheel_dt),
           std::nullopt, static_cast<int>(w - summary.wheels.data()), dt / wheel_dt});
  }
  const WheelSummary* w = most_unloaded(summary, false);
  if (!w || !(fraction(*w) < kWheelEscalationFraction)) return out;
  const double kept = fraction(*w);
  const int wheel = static_cast<int>(w - summary.wheels.data());
  if (law == "linear-hertz")
    out.push_back(
        {"linear_hertz_unloaded",
         fmt::format("wheel {} fell to {:.0f} % of its static load under {}: linearized Hertz was measured within "
                     "1 % of nonlinear Hertz on dQ/Q only while every wheel keeps {:g} % of its load; beyond, at "
                     "dt/4, its minimum contact force was -4.2 % and dQ/Q +1.9 % off (ICE3 over a German high "
                     "profile at 400 km/h; docs/accuracy-and-price.md \"Wheel values\"); \"fidelity\": \"auto\" "
                     "repeats such a run with nonlinear unilateral Hertz",
                     w->name, 100.0 * kept, who_ran(summary), 100.0 * kWheelEscalationFraction),
         std::nullopt, wheel, kept});
  return out;
}

}  // namespace railvsi
