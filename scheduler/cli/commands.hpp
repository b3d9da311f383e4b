#pragma once
// The subcommands of vsi (DESIGN.md "Command line contract").
#include <optional>
#include <string>

#include "core/input_error.hpp"

namespace railvsi::cli {

enum ExitCode : int {
  kExitOk = 0,
  kExitRuntimeFailure = 1,  // the run diverged or did not converge
  kExitInvalidInput = 2,    // bad input or usage
  kExitStudyFailedJobs = 3,
};

struct SimulateArgs {
  std::string scene_file;
  std::optional<std::string> histories_dir;
  bool allow_large = false;  // run beyond the size limits (steps, history memory)
};

struct InspectArgs {
  std::string file;
  int modes = 6;
  std::string format = "text";  // "text" or "json"
};

int simulate_command(const SimulateArgs& args);
int validate_command(const std::string& file);
// Exit 1 when the modal analysis of a scene's structure fails.
int inspect_command(const InspectArgs& args);

// "error: <file>: <json path>: <message>" on stderr.
void report_input_error(const InputError& e);

}  // namespace railvsi::cli
