#pragma once
// The subcommands of vsi (README "Commands").
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "core/input_error.hpp"
#include "simulation/scene.hpp"

namespace railvsi::cli {

enum ExitCode : int {
  kExitOk = 0,
  kExitRuntimeFailure = 1,  // the run diverged or did not converge
  kExitInvalidInput = 2,    // bad input or usage
  kExitStudyFailedJobs = 3,
  kExitCheckFailed = 4,      // --fail-on-exceeded: a check failed
  kExitCheckIncomplete = 5,  // --fail-on-exceeded: a check has cases without a value
};

struct SimulateArgs {
  std::string scene_file;
  std::optional<std::string> histories_dir;
  bool allow_large = false;  // run beyond the size limits (steps, history memory)
  bool verify = false;       // run again at dt/2 and compare the key quantities
};

struct ReplayArgs {
  std::string db = "vsi-results.sqlite";
  std::string job_id;  // id or a prefix of at least 6 hex digits
  std::optional<std::string> histories_dir;
};

struct InspectArgs {
  std::string file;
  int modes = 6;
  std::string format = "text";  // "text" or "json"
};

int simulate_command(const SimulateArgs& args);
// Runs a scene, writes its histories when asked, prints the summary JSON.
// cutoff_hz: the code filter's cut-off (a stored job's), else from the
// structure. allow_large lifts the size limits of a run. Exit 0 when the
// run is ok, else 1. verify: also run the scene at dt/2 and add the
// relative change of each key quantity ("dt_self_check", with a warning per
// value that moves more than the scene's accuracy.tolerance).
int run_scene(Scene scene, const std::string& file_for_errors, std::optional<double> cutoff_hz,
              const std::optional<std::string>& histories_dir, bool allow_large = false, bool verify = false);
// Runs a stored job again from job_scenes.scene (vsi replay).
int replay_command(const ReplayArgs& args);
int validate_command(const std::string& file);
// Exit 1 when the modal analysis of a scene's structure fails.
int inspect_command(const InspectArgs& args);

// A study names study.schema.json in "$schema" or lists "trains"; the
// engine's document kinds know nothing of studies.
bool is_study_document(const nlohmann::json& doc);

// Throws InputError when `file` is not a study, saying what it is and which
// command takes it (a scene: vsi simulate).
void require_study_file(const std::string& file);

// "error: <file>: <json path>: <message>" on stderr.
void report_input_error(const InputError& e);

}  // namespace railvsi::cli
