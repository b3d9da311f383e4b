#include "analysis/modal_run_warnings.hpp"

#include "analysis/modal_moving_forces.hpp"
#include "simulation/run_monitor.hpp"
#include "simulation/track_entry.hpp"

namespace railvsi {

std::vector<RunWarning> modal_run_warnings(const Scene& scene) {
  std::vector<RunWarning> out = scene_input_warnings(scene);
  std::vector<double> offsets;
  for (const MovingForce& m : scene.train.moving_forces) offsets.push_back(m.offset_m);
  if (std::optional<RunWarning> entry = track_entry_warning(scene, offsets, modal_run_start_x_m(scene)))
    out.push_back(std::move(*entry));
  return out;
}

}  // namespace railvsi
