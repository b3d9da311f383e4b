#include <iostream>

#include <fmt/format.h>

#include "cli/commands.hpp"
#include "cli/histories_csv.hpp"
#include "cli/summary_json.hpp"
#include "envelopes/code_filter.hpp"
#include "io/scene_loader.hpp"
#include "planning/time_step_warnings.hpp"
#include "simulation/simulation.hpp"
#include "study/deck_frequencies.hpp"

namespace railvsi::cli {
namespace {

// Structures up to this size get their f0 and f3 (a few Lanczos pairs, well
// under a second for plane models); larger ones use the code frequency's
// floor of 30 Hz, which can only make the dt check more lenient.
constexpr int kMaxDofsForModes = 20000;

double code_cutoff_of(const Scene& scene, std::vector<RunWarning>& warnings) {
  if (scene.structure->num_dofs() <= kMaxDofsForModes) {
    const scheduler::DeckFrequencies f = scheduler::deck_frequencies(*scene.structure);
    return code_cutoff_hz(f.f0_hz, f.f3_hz);
  }
  warnings.push_back({"cutoff_not_computed",
                      fmt::format("the structure has {} DOFs: its deck frequencies were not computed, the time-step "
                                  "checks use the code frequency's floor of 30 Hz",
                                  scene.structure->num_dofs()),
                      std::nullopt, std::nullopt, std::nullopt});
  return code_cutoff_hz(0.0, 0.0);
}

}  // namespace

int simulate_command(const SimulateArgs& args) {
  Scene scene = load_scene(args.scene_file);
  scene.analysis.allow_large_run = args.allow_large;
  // Setup problems the engine finds (a mechanism, a train its wheels cannot
  // carry, a run too large) are input errors of this scene file.
  const Simulation simulation = [&] {
    try {
      return Simulation(scene);
    } catch (const InputError& e) {
      throw e.with_file(args.scene_file);
    }
  }();
  Result result = simulation.run();
  std::vector<RunWarning> extra;
  const double cutoff_hz = code_cutoff_of(scene, extra);
  for (RunWarning& w : time_step_warnings(scene, cutoff_hz)) extra.push_back(std::move(w));
  for (RunWarning& w : extra) result.summary.warnings.push_back(std::move(w));
  if (args.histories_dir) write_histories(result.histories, *args.histories_dir);
  std::cout << summary_json(result, scene.train.is_moving_forces()).dump(2) << '\n';
  return result.status.ok() ? kExitOk : kExitRuntimeFailure;
}

}  // namespace railvsi::cli
