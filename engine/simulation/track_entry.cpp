#include "simulation/track_entry.hpp"

#include <algorithm>
#include <limits>

#include <fmt/format.h>

#include "simulation/evaluation_window.hpp"
#include "simulation/train_layout.hpp"

namespace railvsi {

// Axles that start behind a modelled approach track enter it at its rail
// end during the run: a transient (an axle load applied at once, or a
// wheel leaving the rigid path) that a real track does not have. It is
// inside the evaluation window when the train's first axle is already in
// the window at that moment. Without an approach (the rail starts at the
// bridge) the entry is the bridge's own.
std::optional<RunWarning> track_entry_warning(const Scene& scene, const std::vector<double>& axle_offsets_m,
                                              double start_x_m) {
  if (!(scene.speed_mps > 0.0)) return std::nullopt;
  const StructureModel& st = *scene.structure;
  const double rail_start = st.rails().front().start_m();
  const double bridge_start = bridge_extent_m(st).first;
  const EvaluationWindow window = EvaluationWindow::of(scene);
  double worst_front_m = -std::numeric_limits<double>::infinity();
  for (double off : axle_offsets_m)
    if (TrainLayout::position_m(start_x_m, off) < rail_start)
      worst_front_m = std::max(worst_front_m, rail_start + off);  // front when this axle enters
  if (!(rail_start < bridge_start && worst_front_m >= window.start_m)) return std::nullopt;
  return RunWarning{"entry_inside_window",
                    fmt::format("axles enter the modelled track (x = {:.1f} m) while the first axle is at x = {:.1f} "
                                "m, inside the evaluation window from {:.1f} m: the entry transient is part of the "
                                "results; lengthen the approach track",
                                rail_start, worst_front_m, window.start_m),
                    (worst_front_m - start_x_m) / scene.speed_mps,
                    {},
                    {}};
}

}  // namespace railvsi
