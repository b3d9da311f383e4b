#pragma once
// `vsi generate deck-3d`: writes a generated 3D structure as the files of the
// import path, with two example scenes that run on it.
#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "cli/command_group.hpp"

namespace railvsi::cli {

struct GenerateArgs {
  long dofs = 0;  // required: a default size would hide a 230,000-DOF run
  bool force = false;  // write into a non-empty --out
  std::string out_dir;
  std::vector<double> spans_m{25.0, 25.0, 25.0};
  std::string spans_text;  // --spans as given ("25,30"), parsed into spans_m
  double approach_m = 400.0;
  std::string section_file;  // a deck-section document; empty: the solid default
};

class GenerateCommand final : public CommandGroup {
 public:
  // Adds "generate" (with its subcommand "deck-3d") to app.
  explicit GenerateCommand(CLI::App& app);
  // After app.parse(): the exit code when "generate" was parsed, else nullopt.
  std::optional<int> run_parsed() const override;

 private:
  GenerateArgs args_;
  CLI::App* generate_ = nullptr;
};

// Writes K.mtx, M.mtx, C.mtx, map.json, moving_forces.json and
// multibody.json into args.out_dir and prints a JSON summary on stdout.
int generate_deck_3d_command(const GenerateArgs& args);

}  // namespace railvsi::cli
