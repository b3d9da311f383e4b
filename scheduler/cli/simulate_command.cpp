#include <iostream>
#include <iterator>

#include "cli/commands.hpp"
#include "cli/run_outputs.hpp"
#include "io/json_document.hpp"
#include "io/scene_loader.hpp"
#include "simulation/simulation.hpp"

namespace railvsi::cli {

int run_scene(const Scene& scene, const std::string& file_for_errors, std::optional<double> cutoff_hz,
              const std::optional<std::string>& histories_dir) {
  // Setup problems the engine finds (a mechanism, a train its wheels cannot
  // carry) are input errors of this scene.
  const Simulation simulation = [&] {
    try {
      return Simulation(scene);
    } catch (const InputError& e) {
      throw e.with_file(file_for_errors);
    }
  }();
  const RunFrame frame = run_frame(scene, cutoff_hz);
  const Result result = simulation.run();
  if (histories_dir) write_run_histories(result.histories, frame, *histories_dir);
  std::cout << run_summary_json(result, scene, frame).dump(2) << '\n';
  return result.status.ok() ? kExitOk : kExitRuntimeFailure;
}

int simulate_command(const SimulateArgs& args) {
  if (args.scene_file == "-") {
    // The scene on stdin: relative file names resolve from the working directory.
    const std::string text{std::istreambuf_iterator<char>(std::cin), std::istreambuf_iterator<char>()};
    const Scene scene = parse_scene(parse_json_text(text, "<stdin>"), std::filesystem::current_path(), "<stdin>");
    return run_scene(scene, "<stdin>", std::nullopt, args.histories_dir);
  }
  return run_scene(load_scene(args.scene_file), args.scene_file, std::nullopt, args.histories_dir);
}

}  // namespace railvsi::cli
