#pragma once
// Run-health warnings that need the time-step policy and the code filter
// (README "Run health"): a user's dt above the policy's step
// (dt_above_policy, with the factor and the binding bound) and a Nyquist
// frequency below the code cut-off (filter_above_nyquist: the filtered
// deck acceleration cannot be computed and is left out, never a number).
#include <vector>

#include "simulation/result.hpp"
#include "simulation/scene.hpp"

namespace railvsi {

// cutoff_hz: the code frequency max(30 Hz, 1.5 f0, f3) of the structure.
std::vector<RunWarning> time_step_warnings(const Scene& scene, double cutoff_hz);

}  // namespace railvsi
