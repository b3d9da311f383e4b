#include <iostream>

#include "cli/commands.hpp"
#include "cli/histories_csv.hpp"
#include "cli/summary_json.hpp"
#include "io/scene_loader.hpp"
#include "simulation/simulation.hpp"

namespace railvsi::cli {

int simulate_command(const SimulateArgs& args) {
  const Scene scene = load_scene(args.scene_file);
  // Setup problems the engine finds (a mechanism, a train its wheels cannot
  // carry) are input errors of this scene file.
  const Simulation simulation = [&] {
    try {
      return Simulation(scene);
    } catch (const InputError& e) {
      throw e.with_file(args.scene_file);
    }
  }();
  const Result result = simulation.run();
  if (args.histories_dir) write_histories(result.histories, *args.histories_dir);
  std::cout << summary_json(result, scene.train.is_moving_forces()).dump(2) << '\n';
  return result.status.ok() ? kExitOk : kExitRuntimeFailure;
}

}  // namespace railvsi::cli
