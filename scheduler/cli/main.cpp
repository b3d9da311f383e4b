// vsi: the railvsi command line. Exit codes: 0 success, 1 runtime failure,
// 2 invalid input or usage; whatever happens, main reports it and returns.
#include <exception>
#include <memory>
#include <optional>
#include <vector>
#include <new>
#include <iostream>
#include <string_view>

#include <CLI/CLI.hpp>

#include "cli/command_group.hpp"
#include "cli/commands.hpp"
#include "cli/generate_command.hpp"
#include "cli/price_command.hpp"
#include "cli/report_command.hpp"
#include "cli/scene_commands.hpp"
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

  // Every command, one registration style (cli/command_group.hpp).
  std::vector<std::unique_ptr<CommandGroup>> groups;
  groups.push_back(std::make_unique<SceneCommands>(app));
  groups.push_back(std::make_unique<ServiceCommands>(app));
  groups.push_back(std::make_unique<GenerateCommand>(app));
  groups.push_back(std::make_unique<ReportCommand>(app));
  groups.push_back(std::make_unique<PriceCommand>(app));
  groups.push_back(std::make_unique<ClusterCommands>(app));
  groups.push_back(std::make_unique<ServeCommand>(app));

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
  for (const auto& group : groups)
    if (const std::optional<int> code = group->run_parsed()) return *code;
  // require_subcommand(1) makes this unreachable; no command is a default.
  std::cerr << "error: no command was given (vsi --help)\n";
  return kExitInvalidInput;
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
