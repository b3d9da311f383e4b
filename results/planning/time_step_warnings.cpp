#include "planning/time_step_warnings.hpp"

#include <algorithm>
#include <fmt/format.h>

#include "envelopes/code_filter.hpp"
#include "planning/time_step_policy.hpp"

namespace railvsi {
namespace {

void add_nyquist_warning(double dt, double cutoff_hz, std::vector<RunWarning>& out) {
  const double nyquist_hz = 0.5 / dt;
  if (nyquist_hz < cutoff_hz)
    out.push_back({"filter_above_nyquist",
                   fmt::format("the Nyquist frequency 1/(2 dt) = {:.3g} Hz is below the code cut-off {:.3g} Hz: no "
                               "filtered deck acceleration can be computed (left out)",
                               nyquist_hz, cutoff_hz),
                   std::nullopt, std::nullopt, cutoff_hz / nyquist_hz});
}

}  // namespace

std::vector<RunWarning> time_step_warnings(const Scene& scene, double cutoff_hz) {
  std::vector<RunWarning> out;
  const double dt = scene.analysis.dt_s;
  TimeStepPolicy policy;
  policy.hht = scene.analysis.hht;
  // f0 = 0, f3 = cutoff: the policy's code frequency is then cutoff_hz.
  const TimeStepChoice c = choose_time_step(*scene.structure, scene.train, scene.speed_mps, scene.analysis.contact,
                                            0.0, cutoff_hz, policy, scene.irregularity.get());
  // The policy's requirement, not its ladder rung: a dt between the two is
  // within every bound.
  if (dt > c.required_dt_s * (1.0 + 1e-9)) {
    const auto binding = std::find_if(c.bounds.begin(), c.bounds.end(),
                                      [&](const TimeStepBound& b) { return b.name == c.binding; });
    // The code-frequency detail names f0 and f3, which are not known here.
    const std::string detail =
        c.binding == "code frequency"
            ? fmt::format("f_cut = {:.1f} Hz with HHT period error <= {:g} %", code_cutoff_hz(0.0, cutoff_hz),
                          100.0 * policy.max_period_error)
            : binding->detail;
    out.push_back({"dt_above_policy",
                   fmt::format("dt = {:.3g} s is {:.3g} x the time-step policy's {:.3g} s (binding bound: {}, {}); "
                               "results are not converged to the policy's accuracy",
                               dt, dt / c.required_dt_s, c.required_dt_s, c.binding, detail),
                   std::nullopt, std::nullopt, dt / c.required_dt_s});
  }
  add_nyquist_warning(dt, cutoff_hz, out);
  return out;
}

ModalPeaks modal_peaks_of(const Scene& scene) {
  if (scene.structure->rails().size() >= 2) return ModalPeaks::kSampled;
  return scene.fidelity.asks_section_forces() ? ModalPeaks::kRefinedWithSections : ModalPeaks::kRefined;
}

std::vector<RunWarning> modal_time_step_warnings(const Scene& scene, double cutoff_hz) {
  std::vector<RunWarning> out;
  const double dt = scene.analysis.dt_s;
  const ModalPeaks peaks = modal_peaks_of(scene);
  const double rule_s = modal_time_step_s(cutoff_hz, scene.fidelity.tolerance, peaks);
  if (dt > rule_s * (1.0 + 1e-9))
    out.push_back({"dt_above_policy",
                   fmt::format("dt = {:.3g} s is {:.3g} x the modal rung's {:.3g} s (binding bound: the peak at the "
                               "code frequency {:.1f} Hz {} within the tolerance {:g}); results are not converged to "
                               "the policy's accuracy",
                               dt, dt / rule_s, rule_s, cutoff_hz,
                               peaks == ModalPeaks::kSampled              ? "sampled"
                               : peaks == ModalPeaks::kRefinedWithSections ? "refined, with section forces,"
                                                                          : "refined between samples",
                               scene.fidelity.tolerance),
                   std::nullopt, std::nullopt, dt / rule_s});
  add_nyquist_warning(dt, cutoff_hz, out);
  return out;
}

}  // namespace railvsi
