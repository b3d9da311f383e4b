#include <iostream>

#include "cli/commands.hpp"
#include "cli/histories_csv.hpp"
#include "io/scene_loader.hpp"
#include "simulation/simulation.hpp"
#include "cli/summary_json.hpp"

namespace railvsi::cli {
namespace {

// Runs the scene; input problems the engine finds while setting up (a
// mechanism, a train its wheels cannot carry) are input errors of the scene.
Result run_scene(const Scene& scene, const std::string& scene_file) {
  try {
    const Simulation simulation(scene);
    return simulation.run();
  } catch (const InputError& e) {
    throw e.with_file(scene_file);
  }
}

// The engine reports setup problems as a status whose message is
// "<json path>: <what>" (InputError::describe without a file).
InputError invalid_input_error(const Status& status, const std::string& scene_file) {
  const std::string& message = status.message();
  const auto colon = message.find(": ");
  if (message.starts_with("/") && colon != std::string::npos)
    return InputError(message.substr(0, colon), message.substr(colon + 2), scene_file);
  return InputError("/", message, scene_file);
}

}  // namespace

int simulate_command(const SimulateArgs& args) {
  const Scene scene = load_scene(args.scene_file);
  const Result result = run_scene(scene, args.scene_file);
  // Nothing was computed that could be reported: no summary, as for any bad input.
  if (result.status.code() == StatusCode::kInvalidInput) throw invalid_input_error(result.status, args.scene_file);
  if (args.histories_dir) write_histories(result.histories, *args.histories_dir);
  std::cout << summary_json(result, scene.train.is_moving_forces()).dump(2) << '\n';
  return result.status.ok() ? kExitOk : kExitRuntimeFailure;
}

}  // namespace railvsi::cli
