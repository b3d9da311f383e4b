// vsi: the railvsi command line. Exit codes: 0 success, 1 runtime failure,
// 2 invalid input or usage; whatever happens, main reports it and returns.
#include <exception>
#include <new>
#include <iostream>
#include <string_view>

#include <CLI/CLI.hpp>

#include "cli/commands.hpp"
#include "cli/generate_command.hpp"
#include "cli/price_command.hpp"
#include "cli/report_command.hpp"
#include "cli/serve_command.hpp"
#include "cli/service_commands.hpp"
#include "cli/shard_command.hpp"
#include "core/freed_memory.hpp"
#include "core/huge_pages.hpp"
#include "core/terminal_text.hpp"
#include "store/sqlite.hpp"

namespace railvsi::cli {
namespace {

int run(int argc, char** argv) {
  CLI::App app{"railvsi: nonlinear vehicle-structure interaction of railway bridges", "vsi"};
  app.set_version_flag("--version", "vsi " RAILVSI_VERSION);
  app.require_subcommand(1);

  SimulateArgs simulate_args;
  CLI::App* simulate = app.add_subcommand("simulate", "Run one scene and print its summary JSON on stdout");
  simulate->add_option("scene", simulate_args.scene_file, "Scene file (JSON, schemas/scene.schema.json); - reads stdin")
      ->required();
  simulate->add_option("--histories", simulate_args.histories_dir,
                       "Directory for the time histories: deck.csv (with the first axle's x, the evaluation window "
                       "and the filtered deck acceleration), and for multibody trains contact_forces.csv and "
                       "carbody.csv (created if needed)");
  simulate->add_flag("--allow-large", simulate_args.allow_large,
                     "Run even when the estimated step count, history memory or work exceeds the limits");
  simulate->add_flag("--verify", simulate_args.verify,
                     "Run the scene again at dt/2 and add dt_self_check: the relative change of each key quantity, "
                     "with a dt_self_check warning for each one that moves more than accuracy.tolerance (default 1 %)");

  ReplayArgs replay_args;
  CLI::App* replay = app.add_subcommand(
      "replay", "Run a job of a study database again from its stored scene; print its summary JSON and write its "
                "histories, to reconcile with the envelopes vsi query shows");
  replay->add_option("job", replay_args.job_id, "Job id, or a prefix of at least 6 hex digits")->required();
  replay->add_option("--db", replay_args.db, "Study database (SQLite file)")->capture_default_str();
  replay->add_option("--histories", replay_args.histories_dir, "Directory for the time histories, as vsi simulate");

  std::string validate_file;
  CLI::App* validate = app.add_subcommand(
      "validate", "Check a scene, train or irregularity profile: schema, then every semantic check of a run");
  validate->add_option("file", validate_file, "Document (JSON)")->required();

  InspectArgs inspect_args;
  CLI::App* inspect = app.add_subcommand(
      "inspect", "Report what a scene, study, train or irregularity profile holds: structure DOFs, damping, the "
                 "lowest natural frequencies with their mode types, axles and static loads, profile statistics, the "
                 "HSLM resonance speeds");
  inspect->add_option("file", inspect_args.file, "Document (JSON)")->required();
  inspect->add_option("--modes", inspect_args.modes, "Number of natural frequencies to compute (default 6)")
      ->check(CLI::Range(1, 1000));
  inspect->add_option("--format", inspect_args.format, "Output format: text (default) or json")
      ->check(CLI::IsMember({"text", "json"}));

  ServiceCommands service(app);
  GenerateCommand generate(app);
  ReportCommand report(app);
  PriceCommand price(app);
  ClusterCommands cluster(app);
  ServeCommand serve(app);

  // A word that is no command: CLI11 would say "A subcommand is required".
  if (argc > 1 && argv[1][0] != '-') {
    std::string names;
    bool known = false;
    for (const CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; })) {
      names += (names.empty() ? "" : ", ") + sub->get_name();
      known = known || sub->get_name() == argv[1];
    }
    if (!known) {
      std::cerr << "error: unknown command '" << scheduler::terminal_safe(argv[1]) << "'; the commands are: " << names
                << " (vsi --help)\n";
      return kExitInvalidInput;
    }
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? kExitOk : kExitInvalidInput;  // help and --version are successes
  }
  if (simulate->parsed()) return simulate_command(simulate_args);
  if (replay->parsed()) return replay_command(replay_args);
  if (inspect->parsed()) return inspect_command(inspect_args);
  if (const auto code = service.run_parsed()) return *code;
  if (const auto code = generate.run_parsed()) return *code;
  if (const auto code = report.run_parsed()) return *code;
  if (const auto code = price.run_parsed()) return *code;
  if (const auto code = cluster.run_parsed()) return *code;
  if (const auto code = serve.run_parsed()) return *code;
  return validate_command(validate_file);
}

}  // namespace

// Messages carry user strings (file names, names, values): escaped, so that
// they cannot drive the terminal.
void report_input_error(const InputError& e) {
  std::cerr << "error: " << scheduler::terminal_safe(e.describe()) << '\n';
}

// Whether the command (the first argument that is not an option; vsi's own
// options are flags) runs jobs side by side.
bool runs_jobs_side_by_side(int argc, char** argv) {
  for (int i = 1; i < argc; ++i) {
    const std::string_view a = argv[i];
    if (a.starts_with("-")) continue;
    for (const std::string_view c : {"submit", "work", "run", "status", "query", "cancel", "retry", "check", "shard",
                                     "price", "serve"})
      if (a == c) return true;
    return false;
  }
  return false;
}

}  // namespace railvsi::cli

int main(int argc, char** argv) {
  using namespace railvsi::cli;
  // Before anything is read: a seed-scale run sets up in half the time. The
  // commands that run jobs side by side (they call single_threaded_blas())
  // also start OpenBLAS with one thread; simulate, inspect and generate keep
  // its threads for their large factorizations.
  const bool workers = runs_jobs_side_by_side(argc, argv);
  railvsi::reexec_with_huge_pages(argv, workers);
  // Workers reuse their buffers job after job: keep them mapped, in the
  // heap the main thread has faulted in already.
  railvsi::keep_freed_memory();
  if (workers) railvsi::one_heap_for_all_threads();
  try {
    return run(argc, argv);
  } catch (const railvsi::InputError& e) {
    report_input_error(e);
    return kExitInvalidInput;
  } catch (const railvsi::scheduler::NoSuchDatabase& e) {  // --db names no store (replay, report, price)
    std::cerr << "error: " << railvsi::scheduler::terminal_safe(e.what()) << '\n';
    return kExitInvalidInput;
  } catch (const std::bad_alloc&) {
    // Inputs are sized before allocating; this is a last resort, not a path.
    std::cerr << "error: out of memory\n";
    return kExitRuntimeFailure;
  } catch (const std::exception& e) {
    std::cerr << "error: " << railvsi::scheduler::terminal_safe(e.what()) << '\n';
    return kExitRuntimeFailure;
  } catch (...) {
    std::cerr << "error: unexpected failure\n";
    return kExitRuntimeFailure;
  }
}
