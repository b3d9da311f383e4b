#pragma once
// What a modal moving-force run records besides its maxima, as the FE
// rungs' RunMonitor does for the same scene: the input warnings
// (scene_input_warnings) and the rail-end entry inside the evaluation
// window (entry_inside_window, simulation/track_entry.hpp). The modal rung
// has no monitor; run_modal_moving_forces and the workers' batched modal
// jobs both take these.
#include <vector>

#include "simulation/result.hpp"
#include "simulation/scene.hpp"

namespace railvsi {

std::vector<RunWarning> modal_run_warnings(const Scene& scene);

}  // namespace railvsi
