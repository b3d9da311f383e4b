#pragma once
// Run-health warnings on the wheel values (minimum contact force, dQ/Q,
// contact-loss time) of a run in which a wheel unloaded far, for the runs
// the planner's escalation (effects_planner.hpp, kWheelEscalationFraction)
// does not cover: a pinned rung or the analysis as given.
//   wheel_values_dt: a compliant contact law at a dt within the policy's
//     but above kWheelEscalationDtFactor x its ladder step;
//   linear_hertz_unloaded: linearized Hertz past the unloading up to which
//     it was measured against nonlinear Hertz.
// Each names the wheel, the law and rung that ran and what was measured.
#include <vector>

#include "simulation/result.hpp"
#include "simulation/scene.hpp"

namespace railvsi {

// scene: as it ran (scene_as_run: its contact law and dt); cutoff_hz: the
// code frequency of the structure, as for time_step_warnings.
std::vector<RunWarning> wheel_value_warnings(const Scene& scene, const RunSummary& summary, double cutoff_hz);

}  // namespace railvsi
