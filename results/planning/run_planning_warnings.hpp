#pragma once
// The warnings a finished run gets from the planning layer, the same for
// `vsi simulate`, the workers and `vsi price`: its dt against the time-step
// policy (time_step_warnings.hpp; on the exact modal rung its sampling
// rule) and its wheel values (wheel_value_warnings.hpp).
#include <vector>

#include "simulation/result.hpp"
#include "simulation/scene.hpp"

namespace railvsi {

// ran: the scene as it ran (scene_as_run: the contact law and dt of the
// run); cutoff_hz: the code frequency of the structure.
std::vector<RunWarning> run_planning_warnings(const Scene& ran, const RunSummary& summary, double cutoff_hz);

}  // namespace railvsi
