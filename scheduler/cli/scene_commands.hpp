#pragma once
// The commands on one document: `vsi simulate`, `replay` (a stored job),
// `validate` and `inspect`.
#include <string>

#include <CLI/CLI.hpp>

#include "cli/command_group.hpp"
#include "cli/commands.hpp"

namespace railvsi::cli {

class SceneCommands final : public CommandGroup {
 public:
  explicit SceneCommands(CLI::App& app);
  std::optional<int> run_parsed() const override;

 private:
  SimulateArgs simulate_args_;
  ReplayArgs replay_args_;
  std::string validate_file_;
  InspectArgs inspect_args_;
  CLI::App *simulate_ = nullptr, *replay_ = nullptr, *validate_ = nullptr, *inspect_ = nullptr;
};

}  // namespace railvsi::cli
