#pragma once
// The rail-end entry: axles that start behind the modelled approach track
// enter it during the run, a transient a real track does not have. Every
// rung records it the same way: the FE rungs' RunMonitor and the modal
// moving-force rung, which has no monitor.
#include <optional>
#include <vector>

#include "simulation/result.hpp"
#include "simulation/scene.hpp"

namespace railvsi {

// entry_inside_window when axles at `axle_offsets_m` behind the first,
// which starts at start_x_m, enter the modelled track at its rail end while
// the first axle is inside the evaluation window; none otherwise (no speed,
// no approach track, or every entry before the window).
std::optional<RunWarning> track_entry_warning(const Scene& scene, const std::vector<double>& axle_offsets_m,
                                              double start_x_m);

}  // namespace railvsi
