#include <iostream>
#include <iterator>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "cli/commands.hpp"
#include "cli/run_outputs.hpp"
#include "envelopes/code_filter.hpp"
#include "envelopes/job_envelopes.hpp"
#include "core/input_error.hpp"
#include "io/input_file.hpp"
#include "io/json_document.hpp"
#include "io/scene_loader.hpp"
#include "planning/run_planning_warnings.hpp"
#include "price/dt_self_check.hpp"
#include "simulation/simulation.hpp"
#include "planning/deck_frequencies.hpp"
#include "planning/scene_plan.hpp"
#include "planning/rung_runner.hpp"

namespace railvsi::cli {
namespace {

// The deck frequencies, for the code frequency and the planner; zero (not
// known) for a structure too large for a quick modal analysis.
DeckFrequencies frequencies_of(const Scene& scene, std::vector<RunWarning>& warnings) {
  // Larger structures take the code frequency's floor of 30 Hz: a dt check
  // more lenient and a filter cut-off that may be below the code's.
  const int dofs = scene.structure->num_dofs();
  if (dofs <= kMaxDofsForDeckFrequencies) {
    DeckFrequencies f = deck_frequencies(*scene.structure);
    if (f.status.ok()) return f;
    warnings.push_back({"cutoff_not_computed",
                        fmt::format("the modal analysis for the deck frequencies failed ({}): the time-step checks "
                                    "and the code filter use the code frequency's floor of 30 Hz",
                                    f.status.message()),
                        std::nullopt, std::nullopt, std::nullopt});
    return f;
  }
  warnings.push_back({"cutoff_not_computed",
                      fmt::format("the structure has {} DOFs: its deck frequencies were not computed, the time-step "
                                  "checks and the code filter use the code frequency's floor of 30 Hz",
                                  dofs),
                      std::nullopt, std::nullopt, std::nullopt});
  return {};
}

// vsi simulate --verify: the scene again at half its step, planned as the
// first run was (the same frequencies; a rung that escalates does so at
// half its step too), and the key quantities of both compared.
DtSelfCheck verify_dt(const Scene& scene, const Result& first, const DeckFrequencies& f, double cutoff_hz,
                      const std::string& file_for_errors, std::vector<RunWarning>& warnings) {
  Scene half = scene;
  half.analysis.dt_s = 0.5 * scene.analysis.dt_s;
  const Result fine = [&] {
    try {
      return run_planned(half, f);
    } catch (const InputError& e) {
      throw e.with_file(file_for_errors);
    }
  }();
  const JobEnvelopes a = compute_envelopes(first, first.summary.dt_s, scene.analysis.history_stride, cutoff_hz);
  const JobEnvelopes b = compute_envelopes(fine, fine.summary.dt_s, half.analysis.history_stride, cutoff_hz);
  const DtSelfCheck check = dt_self_check(a, b, first.summary.dt_s, fine.summary.dt_s, scene.fidelity.tolerance);
  if (!b.ok())
    warnings.push_back({"dt_self_check",
                        fmt::format("the run at dt/2 ended {} ({}): its values are not a reference", b.status,
                                    b.message.empty() ? fine.status.message() : b.message),
                        std::nullopt, std::nullopt, std::nullopt});
  const auto rung = [](const Result& r) { return r.summary.fidelity.rung + " " + r.summary.fidelity.contact_law; };
  if (rung(fine) != rung(first))
    warnings.push_back({"dt_self_check",
                        fmt::format("the run at dt/2 ran on {}, the run at dt on {}: the check compares rungs as "
                                    "well as steps",
                                    rung(fine), rung(first)),
                        std::nullopt, std::nullopt, std::nullopt});
  for (RunWarning& w : dt_self_check_warnings(check)) warnings.push_back(std::move(w));
  return check;
}

}  // namespace

int run_scene(Scene scene, const std::string& file_for_errors, std::optional<double> cutoff_hz,
              const std::optional<std::string>& histories_dir, bool allow_large, bool verify) {
  scene.analysis.allow_large_run = allow_large;
  std::vector<RunWarning> extra;
  const bool need_frequencies = !cutoff_hz || scene.fidelity.mode != FidelityRequest::Mode::kAsGiven;
  const DeckFrequencies f = need_frequencies ? frequencies_of(scene, extra) : DeckFrequencies{};
  const double cutoff = cutoff_hz ? *cutoff_hz : code_cutoff_hz(f.f0_hz, f.f3_hz);
  // The default free vibration lasts at least 3 periods of f0.
  scene.analysis.structure_f0_hz = f.f0_hz;
  // Setup problems the engine finds (a mechanism, a train its wheels cannot
  // carry, a run too large) are input errors of this scene.
  Result result = [&] {
    try {
      return run_planned(scene, f);
    } catch (const InputError& e) {
      throw e.with_file(file_for_errors);
    }
  }();
  std::optional<DtSelfCheck> check;
  if (verify) check = verify_dt(scene, result, f, cutoff, file_for_errors, extra);
  // An escalation for wheel quantities ran at a finer dt: its histories and filter are at that dt.
  if (result.summary.dt_s > 0.0) scene.analysis.dt_s = result.summary.dt_s;
  // The time-step checks judge the contact law that ran (the planner's for "auto").
  const Scene ran = scene_as_run(scene, result.summary);
  for (RunWarning& w : run_planning_warnings(ran, result.summary, cutoff)) extra.push_back(std::move(w));
  for (RunWarning& w : extra) result.summary.warnings.push_back(std::move(w));
  const RunFrame frame = run_frame(scene, cutoff);
  if (histories_dir) write_run_histories(result.histories, frame, *histories_dir);
  nlohmann::ordered_json summary = run_summary_json(result, scene, frame);
  if (check) summary["dt_self_check"] = dt_self_check_json(*check);
  std::cout << summary.dump(2) << '\n';
  return result.status.ok() ? kExitOk : kExitRuntimeFailure;
}

int simulate_command(const SimulateArgs& args) {
  if (args.scene_file == "-") {
    // The scene on stdin: relative file names resolve from the working directory.
    // At most the JSON file limit: `vsi simulate - < /dev/zero` read forever.
    std::string text;
    std::vector<char> chunk(1 << 16);
    while (std::cin.read(chunk.data(), static_cast<std::streamsize>(chunk.size())) || std::cin.gcount() > 0) {
      text.append(chunk.data(), static_cast<std::size_t>(std::cin.gcount()));
      if (text.size() > kMaxJsonFileBytes)
        throw InputError("/", fmt::format("more than {} MiB on standard input: not a plausible scene",
                                          kMaxJsonFileBytes >> 20),
                         "<stdin>");
    }
    const Scene scene = parse_scene(parse_json_text(text, "<stdin>"), std::filesystem::current_path(), "<stdin>");
    return run_scene(scene, "<stdin>", std::nullopt, args.histories_dir, args.allow_large, args.verify);
  }
  return run_scene(load_scene(args.scene_file), args.scene_file, std::nullopt, args.histories_dir, args.allow_large, args.verify);
}

}  // namespace railvsi::cli
