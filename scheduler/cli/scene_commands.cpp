#include "cli/scene_commands.hpp"

namespace railvsi::cli {

SceneCommands::SceneCommands(CLI::App& app) {
  simulate_ = app.add_subcommand("simulate", "Run one scene and print its summary JSON on stdout");
  simulate_->add_option("scene", simulate_args_.scene_file, "Scene file (JSON, schemas/scene.schema.json); - reads stdin")
      ->required();
  simulate_->add_option("--histories", simulate_args_.histories_dir,
                       "Directory for the time histories: deck.csv (with the first axle's x, the evaluation window "
                       "and the filtered deck acceleration), and for multibody trains contact_forces.csv and "
                       "carbody.csv (created if needed)");
  simulate_->add_flag("--allow-large", simulate_args_.allow_large,
                     "Run even when the estimated step count, history memory or work exceeds the limits");
  simulate_->add_flag("--verify", simulate_args_.verify,
                      "Run the scene again at dt/2 and add dt_self_check: the relative change of each key quantity, "
                      "with a dt_self_check warning for each one that moves more than accuracy.tolerance (default 1 %)");

  replay_ = app.add_subcommand(
      "replay", "Run a job of a study database again from its stored scene; print its summary JSON and write its "
                "histories, to reconcile with the envelopes vsi query shows");
  replay_->add_option("job", replay_args_.job_id, "Job id, or a prefix of at least 6 hex digits")->required();
  replay_->add_option("--db", replay_args_.db, "Study database (SQLite file)")->capture_default_str();
  replay_->add_option("--histories", replay_args_.histories_dir, "Directory for the time histories, as vsi simulate");

  validate_ = app.add_subcommand(
      "validate", "Check a scene, train or irregularity profile: schema, then every semantic check of a run");
  validate_->add_option("file", validate_file_, "Document (JSON)")->required();

  inspect_ = app.add_subcommand(
      "inspect", "Report what a scene, study, train or irregularity profile holds: structure DOFs, damping, the "
                 "lowest natural frequencies with their mode types, axles and static loads, profile statistics, the "
                 "HSLM resonance speeds");
  inspect_->add_option("file", inspect_args_.file, "Document (JSON)")->required();
  inspect_->add_option("--modes", inspect_args_.modes, "Number of natural frequencies to compute (default 6)")
      ->check(CLI::Range(1, 1000));
  inspect_->add_option("--format", inspect_args_.format, "Output format: text (default) or json")
      ->check(CLI::IsMember({"text", "json"}));
}

std::optional<int> SceneCommands::run_parsed() const {
  if (simulate_->parsed()) return simulate_command(simulate_args_);
  if (replay_->parsed()) return replay_command(replay_args_);
  if (validate_->parsed()) return validate_command(validate_file_);
  if (inspect_->parsed()) return inspect_command(inspect_args_);
  return std::nullopt;
}

}  // namespace railvsi::cli
