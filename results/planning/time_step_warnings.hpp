#pragma once
// Run-health warnings that need the time-step policy and the code filter
// (README "Run health"): a user's dt above the policy's step
// (dt_above_policy, with the factor and the binding bound) and a Nyquist
// frequency below the code cut-off (filter_above_nyquist: the filtered
// deck acceleration cannot be computed and is left out, never a number).
#include <vector>

#include "planning/effects_planner.hpp"
#include "simulation/result.hpp"
#include "simulation/scene.hpp"

namespace railvsi {

// cutoff_hz: the code frequency max(30 Hz, 1.5 f0, f3) of the structure.
std::vector<RunWarning> time_step_warnings(const Scene& scene, double cutoff_hz);

// The peaks a modal moving-force run keeps: the deck twist (a structure
// with two rail lines may have one) its largest sample; the deck's and the
// section forces' refined between samples (ModalPeaks).
ModalPeaks modal_peaks_of(const Scene& scene);

// The same warnings on the modal moving-force rung, whose step only samples
// the load and the output: dt above the sampling rule for its peaks
// (modal_time_step_s at the scene's tolerance), and filter_above_nyquist.
std::vector<RunWarning> modal_time_step_warnings(const Scene& scene, double cutoff_hz);

}  // namespace railvsi
